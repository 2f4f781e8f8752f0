// SPDX-License-Identifier: MIT
// Text and Markdown listings of options (io/options_describe.h): every field with type, unit,
// default (or the formula of its derived default), valid range and doc, and the cross checks.
#include "mirage/io/options_describe.h"

#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/test_options.h"

namespace mirage::io {
namespace {

using test::TestTrackerDescriptor;
using ::testing::HasSubstr;

TEST(DescribeText, ListsEveryFieldWithTypeUnitDefaultRangeAndDoc) {
  const std::string text = DescribeText(TestTrackerDescriptor(), "tracker");

  EXPECT_THAT(text, HasSubstr("tracker: test::TestTrackerOptions\n"));
  EXPECT_THAT(text, HasSubstr("\ngate_m  number, m\n"
                              "    default: derived: speed_mps * dt_s + 2 * range_sigma_m (0.3 m without speed_mps, "
                              "dt_s, range_sigma_m)\n"
                              "    valid:   a number > 0 m\n"
                              "    Association gate | half-width.\n"));
  EXPECT_THAT(text, HasSubstr("\nlost_steps  integer, steps\n    default: 3 steps\n    valid:   an integer >= 1 steps\n"));
  EXPECT_THAT(text, HasSubstr("\nmodel  choice\n    default: cir\n    valid:   one of: cir, ranges\n"));
  EXPECT_THAT(text, HasSubstr("\nmotion  section, test::TestMotionOptions\n    Motion model.\n"));
  EXPECT_THAT(text, HasSubstr("\nmotion.accel_sigma_mps2  number, m/s^2\n    default: 0.5 m/s^2\n"));
  EXPECT_THAT(text, HasSubstr("cross-field checks:\n    window_max_m >= window_min_m\n"
                              "    motion: max_accel_mps2 >= accel_sigma_mps2\n"));
  TestTrackerDescriptor().ForEach(TestTrackerDescriptor().defaults(),
                                  [&](const std::string& path, const core::OptionField& field, const void*) {
                                    EXPECT_THAT(text, HasSubstr("\n" + path + "  ")) << path;
                                    EXPECT_THAT(text, HasSubstr(field.doc())) << path;
                                  });
}

TEST(DescribeMarkdown, GivesATablePerSectionWithEveryFieldAndTheChecks) {
  const std::string md = DescribeMarkdown(TestTrackerDescriptor(), "tracker");

  EXPECT_THAT(md, HasSubstr("## `tracker` (`test::TestTrackerOptions`)\n"));
  EXPECT_THAT(md, HasSubstr("### `tracker.motion` (`test::TestMotionOptions`)\n"));
  EXPECT_THAT(md, HasSubstr("| `gate_m` | number | m | derived: speed_mps * dt_s + 2 * range_sigma_m (0.3 without "
                            "speed_mps, dt_s, range_sigma_m) | > 0 | Association gate \\| half-width. |\n"));
  EXPECT_THAT(md, HasSubstr("| `accel_sigma_mps2` | number | m/s^2 | 0.5 | > 0 | White acceleration std. |\n"));
  EXPECT_THAT(md, HasSubstr("| `weight` | choice |  | huber | huber, cauchy | Robust weight. |\n"));
  EXPECT_THAT(md, HasSubstr("- window_max_m >= window_min_m\n"));
  EXPECT_THAT(md, HasSubstr("- max_accel_mps2 >= accel_sigma_mps2\n"));
  std::istringstream lines(md);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) rows += line.rfind("| `", 0) == 0 ? 1 : 0;
  EXPECT_EQ(rows, 12 + 3);
}

}  // namespace
}  // namespace mirage::io
