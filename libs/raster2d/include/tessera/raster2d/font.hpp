#pragma once
// Tessera's one built-in bitmap font: printable ASCII (32-126) drawn as 5 x 8 glyphs on a 6-unit advance, a classic
// "5 x 7 plus a descender row" design (drawn for Tessera: capitals and digits 7 rows tall, lower case 5 rows with one
// row below the baseline for g, j, p, q, y). The Canvas draws it with text() (canvas.hpp); pictures drawn without a
// canvas (the examples' labels) lay it out with text_runs() and stamp the runs themselves.
//
// Font units: one unit is one bitmap pixel. A line's glyph cells are kAdvance units apart; a glyph covers columns
// [0, kGlyphWidth) of its cell, so the last column of the advance is the gap. Rows are counted down from the top of
// the cell: rows [0, kAscent) stand above the baseline, rows [kAscent, kGlyphHeight) below it. Lines are kLineHeight
// units apart (1.25 x the font size, as Processing's leading of about 1.275 x ascent + descent, kept whole so that
// integer scales stay on the pixel grid).
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace tessera {

/// Horizontal text alignment, as Processing's textAlign(alignX): the anchor x is each line's left edge, center or
/// right edge (measured with the advance, as textWidth()).
enum class TextAlignX { left, center, right };
/// Vertical text alignment, as Processing's textAlign(alignX, alignY): the anchor y is the first line's baseline
/// (BASELINE), its top (TOP: y + ascent is the baseline), the middle of its capitals for one line (CENTER: y +
/// (ascent - (lines - 1) leading) / 2), or the last line's bottom (BOTTOM: y - descent - (lines - 1) leading).
enum class TextAlignY { baseline, top, center, bottom };

namespace font {

inline constexpr int kGlyphWidth = 5;             ///< ink columns of a glyph
inline constexpr int kGlyphHeight = 8;            ///< rows of a glyph: kAscent above the baseline, kDescent below
inline constexpr int kAdvance = 6;                ///< from one character's cell to the next (one column of gap)
inline constexpr int kAscent = 7;                 ///< rows above the baseline (capitals and digits fill them all)
inline constexpr int kDescent = 1;                ///< rows below the baseline (g, j, p, q, y and a few signs reach it)
inline constexpr int kSize = kAscent + kDescent;  ///< the font's native size: text_size(kSize) draws one pixel a unit
inline constexpr int kLineHeight = 10;            ///< from one line's baseline to the next

/// A glyph: row r (0 at the top) is rows[r]; bit (kGlyphWidth - 1 - c) of it is column c's ink.
using Glyph = std::array<uint8_t, kGlyphHeight>;

/// The glyph of `c`. Characters outside 32-126 (tab, control characters, bytes of UTF-8 sequences) draw a hollow box.
const Glyph& glyph(char c);

/// A horizontal run of ink, in font units relative to the text's anchor: the unit squares [x0, x1) x [y, y + 1). Line
/// 0's baseline is y = 0, so its rows above the baseline have y = -kAscent ... -1 and its descender row y = 0.
struct TextRun {
  int x0, x1, y;
};

/// The ink of `text` as runs, each line aligned by `align` about x = 0 (its left edge, the center or the right edge of
/// its advance width, which is even, so centers stay whole), line i's baseline at y = i kLineHeight. '\n' starts a new
/// line; '\r' is ignored.
std::vector<TextRun> text_runs(std::string_view text, TextAlignX align = TextAlignX::left);

/// The widest line's advance width in font units (kAdvance per character, '\r' not counted), as Processing's
/// textWidth() of a multi-line string.
int text_width(std::string_view text);

/// The number of lines (1 + the number of '\n'; 1 for the empty string).
int line_count(std::string_view text);

}  // namespace font
}  // namespace tessera
