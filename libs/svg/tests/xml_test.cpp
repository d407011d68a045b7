// The XML reader (xml.cpp), directly and through parse_svg: events, attribute decoding and offsets, well-formedness
// errors naming line and column, and the XML a real SVG file holds (byte order mark, declaration, DOCTYPE, comments,
// CDATA, entities).
#include "xml.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "svg_test_util.hpp"
#include "tessera/svg/svg.hpp"

namespace tessera {
namespace {

using namespace test;
using xml::Event;

// Every event of `text` up to and including Eof.
std::vector<Event> events(std::string_view text, std::string_view root = "doc") {
  const xml::SourceMap map(text, "t.xml");
  xml::Reader reader(text, map, root);
  std::vector<Event> out;
  do out.push_back(reader.next());
  while (out.back().kind != Event::Kind::eof);
  return out;
}

TEST(XmlReader, EventsInDocumentOrder) {
  const std::string text = "<doc a='1'>\n  <e b=\"x&amp;y\"/><f></f>\n</doc>";
  const auto e = events(text);
  ASSERT_EQ(e.size(), 7u);
  const Event::Kind S = Event::Kind::start, E = Event::Kind::end;
  const std::vector<std::pair<Event::Kind, std::string>> expected = {{S, "doc"}, {S, "e"}, {E, "e"},
                                                                     {S, "f"},   {E, "f"}, {E, "doc"}};
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(e[i].kind, expected[i].first) << i;
    EXPECT_EQ(e[i].name, expected[i].second) << i;
  }
  EXPECT_EQ(e[6].kind, Event::Kind::eof);
  // Offsets of each '<' counted by hand; an empty element's End carries its start tag's offset.
  EXPECT_EQ(e[0].offset, 0u);
  EXPECT_EQ(e[1].offset, 14u);
  EXPECT_EQ(e[2].offset, 14u);
  EXPECT_EQ(e[3].offset, 30u);
  EXPECT_EQ(e[4].offset, 33u);
  EXPECT_EQ(e[5].offset, 38u);
}

TEST(XmlReader, AttributesAreDecodedWithTheirOffsets) {
  const auto e = events("<doc a='1' bb = \"x&lt;y\" c='t\tu\nv'/>");
  ASSERT_EQ(e[0].attributes.size(), 3u);
  const xml::Attribute& a = e[0].attributes[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.value, "1");
  EXPECT_EQ(a.name_offset, 5u);
  EXPECT_EQ(a.value_offset, 8u);
  EXPECT_TRUE(a.verbatim);
  const xml::Attribute& b = e[0].attributes[1];
  EXPECT_EQ(b.value, "x<y");
  EXPECT_EQ(b.name_offset, 11u);
  EXPECT_EQ(b.value_offset, 17u);
  EXPECT_FALSE(b.verbatim);                      // an entity shifts the columns inside the value
  EXPECT_EQ(e[0].attributes[2].value, "t u v");  // white space characters become spaces
}

TEST(XmlReader, EofRepeatsAndTheExpectedRootIsNamed) {
  const std::string text = "<doc/>  <!-- after -->\n";
  const xml::SourceMap map(text, "t.xml");
  xml::Reader reader(text, map, "doc");
  EXPECT_EQ(reader.next().kind, Event::Kind::start);
  EXPECT_EQ(reader.next().kind, Event::Kind::end);
  EXPECT_EQ(reader.next().kind, Event::Kind::eof);
  EXPECT_EQ(reader.next().kind, Event::Kind::eof);
  EXPECT_EQ(error_of([] { events(" <!-- only a comment -->", "html"); }),
            "t.xml:1:25: no root element: expected <html>");
  EXPECT_EQ(error_of([] { events("<a>\n<b>\n</a>"); }), "t.xml:3:1: expected </b> to close <b> from line 2, got </a>");
}

TEST(XmlSourceMap, LinesAndColumnsAreOneBasedBytes) {
  const xml::SourceMap map("ab\ncd\n\ne", "f.svg");
  EXPECT_EQ(map.line(0), 1);
  EXPECT_EQ(map.line(2), 1);  // the '\n' ends its line
  EXPECT_EQ(map.line(3), 2);
  EXPECT_EQ(map.line(7), 4);
  EXPECT_EQ(map.where(4), "f.svg:2:2");
  EXPECT_EQ(map.where(6), "f.svg:3:1");
  // The message quotes the document's bytes through printable(): an escape sequence does not reach the terminal.
  EXPECT_EQ(error_of([&] { map.fail(1, "got '\x1b[2J'"); }), "f.svg:1:2: got '\\x1b[2J'");
}

TEST(SvgDocument, XmlFeatures) {
  const auto d = parse_svg(
      "\xef\xbb\xbf<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" \"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\" [\n"
      "  <!ENTITY x \"<>\">\n]>\n<!-- a comment -->\n"
      "<svg width='10' height=\"10\"><![CDATA[ <rect/> ]]><g><!-- <rect/> --></g>\n"
      "<path d='M&#48; 0 L&#x35; 5 5 0' fill='&#x72;&#101;d' stroke=\"rgb(0,0,0)\" "
      "data-x=\"&lt;&amp;&gt;&quot;&apos;\"/>"
      "</svg>\n<!-- trailing -->\n",
      "t.svg");
  ASSERT_EQ(d.shapes.size(), 1u);
  expect_near(d.shapes[0].subpaths[0].segments[0].end, {5, 5});
  expect_color(*d.shapes[0].style.fill, 1, 0, 0);
}
}  // namespace
}  // namespace tessera
