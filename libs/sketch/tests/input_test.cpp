#include "tessera/sketch/input.hpp"

#include <gtest/gtest.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {

TEST(InputScript, ParsesEveryEventKind) {
  const auto events = parse_input_script(
      "# a comment line\n"
      "12 mouse_move 100 80   # trailing comment\n"
      "12 mouse_press left\n"
      "14 mouse_release right\n"
      "\n"
      "20 mouse_wheel -2.5\n"
      "30 key_press a\n"
      "31 key_release up\n"
      "40 window_resize 800 600\n"
      "41 focus_lost\n"
      "42 focus_gained\n");
  ASSERT_EQ(events.size(), 9u);
  EXPECT_EQ(events[0].frame, 12);
  EXPECT_EQ(events[0].kind, InputKind::mouse_move);
  EXPECT_EQ(events[0].x, 100);
  EXPECT_EQ(events[0].y, 80);
  EXPECT_EQ(events[1].kind, InputKind::mouse_press);
  EXPECT_EQ(events[1].button, MouseButton::left);
  EXPECT_EQ(events[2].button, MouseButton::right);
  EXPECT_EQ(events[3].wheel, -2.5);
  EXPECT_EQ(events[4].key, 'a');
  EXPECT_EQ(events[4].key_code, 'A');  // Java's VK_A, as Processing's keyCode
  EXPECT_EQ(events[5].key, Key::coded);
  EXPECT_EQ(events[5].key_code, Key::up);
  EXPECT_EQ(events[6].x, 800);
  EXPECT_EQ(events[7].kind, InputKind::focus_lost);
  EXPECT_EQ(events[8].kind, InputKind::focus_gained);
}

TEST(InputScript, SortsByFrameKeepingOrderWithinAFrame) {
  const auto events = parse_input_script("5 key_press b\n2 mouse_move 1 1\n5 key_release b\n2 mouse_press left\n");
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].kind, InputKind::mouse_move);
  EXPECT_EQ(events[1].kind, InputKind::mouse_press);
  EXPECT_EQ(events[2].kind, InputKind::key_press);
  EXPECT_EQ(events[3].kind, InputKind::key_release);
}

TEST(InputScript, KeyNames) {
  int key = 0, code = 0;
  ASSERT_TRUE(key_from_name("space", key, code));
  EXPECT_EQ(key, ' ');
  ASSERT_TRUE(key_from_name("enter", key, code));
  EXPECT_EQ(key, 10);  // Processing's ENTER
  ASSERT_TRUE(key_from_name("shift", key, code));
  EXPECT_EQ(key, Key::coded);
  EXPECT_EQ(code, 16);  // Processing's SHIFT
  ASSERT_TRUE(key_from_name("7", key, code));
  EXPECT_EQ(key, '7');
  EXPECT_EQ(code, '7');
  EXPECT_FALSE(key_from_name("f13", key, code));
}

void expect_error(const char* script, const char* fragment) {
  try {
    parse_input_script(script, "demo.txt");
    ADD_FAILURE() << "no error for: " << script;
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(InputScript, ErrorsNameTheLineAndWhatWasExpected) {
  expect_error("1 mouse_move 1 1\n\n3 mouse_jump 1 2\n", "demo.txt line 3: unknown event 'mouse_jump'");
  expect_error("0 mouse_move 1 1\n", "line 1: frame 0 is not between 1 and 2^30");
  expect_error("x mouse_move 1 1\n", "line 1: the frame");
  expect_error("2 mouse_move 1\n", "mouse_move takes 2 argument(s), got 1");
  expect_error("2 mouse_press middle\n", "unknown button 'middle'");
  expect_error("2 key_press hyper\n", "unknown key 'hyper'");
  expect_error("2 window_resize 0 10\n", "must be positive");
  expect_error("2\n", "no event after the frame");
}

}  // namespace
}  // namespace tessera
