// SPDX-License-Identifier: MIT
// Track-loss score and relocalization search of MINT (a mirage addition) in the 6 m x 6 m
// square room of square_room.h: hand-built ranges give known matched/visible counts.
#include "mirage/methods/mint/relocalization.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "methods/mint/square_room.h"
#include "mirage/geometry/visibility.h"

namespace mirage::methods::mint {
namespace {

using testing::EmptySquareRoom;
using testing::SquareRoomVas;
using testing::SquareRoomWithPillar;

const Vec2 kAgent(2.0, 2.5);

// Id of the VA of `anchor` with exactly this wall sequence ({} for the anchor itself).
int IdOf(const geometry::VirtualAnchorSet& vas, int anchor, const std::vector<int>& walls) {
  for (const auto& va : vas.all()) {
    if (va.anchor_index == anchor && va.walls == walls) return va.id;
  }
  ADD_FAILURE() << "no VA with the given walls";
  return 0;
}

double RangeTo(const geometry::VirtualAnchorSet& vas, int id, const Vec2& p_m) { return (vas[id].position_m - p_m).norm(); }

// Noise-free ranges of every VA up to order 1 visible from p_m, both anchors.
// The ranges of one anchor.
core::RangeSet Set(int anchor, std::vector<core::RangeMeasurement> ranges) {
  core::RangeSet set;
  set.anchor_index = anchor;
  set.ranges = std::move(ranges);
  return set;
}

std::vector<core::RangeSet> ExactRanges(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                                            const Vec2& p_m) {
  std::vector<core::RangeSet> out;
  for (int a = 0; a < vas.anchor_count(); ++a) {
    core::RangeSet anchor;
    anchor.anchor_index = a;
    for (const int id : geometry::VisibleVirtualAnchors(vas, a, plan, p_m, 1)) anchor.ranges.push_back({RangeTo(vas, id, p_m), 1.0});
    out.push_back(anchor);
  }
  return out;
}

TEST(ScorePosition, CountsRangesWithinTheToleranceAsMatchesOfTheVisibleVas) {
  // Arrange: in the empty square every order-1 VA is visible: 5 per anchor. Anchor 0 gets its
  // LOS exactly, the south-wall VA 4 cm off (inside 5 cm), the east-wall VA 6 cm off (outside)
  // and a clutter range; anchor 1 gets nothing.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);
  const std::vector<core::RangeSet> ranges{
      Set(0, {{RangeTo(vas, IdOf(vas, 0, {}), kAgent), 1.0},
              {RangeTo(vas, IdOf(vas, 0, {0}), kAgent) + 0.04, 0.5},
              {RangeTo(vas, IdOf(vas, 0, {1}), kAgent) - 0.06, 0.5},
              {9.5, 0.1}}),
      Set(1, {})};
  const RelocalizationOptions options;

  // Act
  const MatchScore score = ScorePosition(vas, plan, kAgent, ranges, options);

  // Assert
  EXPECT_EQ(score.visible, 10);
  EXPECT_EQ(score.matched, 2);
  EXPECT_DOUBLE_EQ(score.fraction(), 0.2);
}

TEST(ScorePosition, CountsOnlyTheAnchorsThatHaveMeasurementsAndOnlyUpToMaxOrder) {
  // Arrange: all exact ranges of anchor 1, no entry at all for anchor 0.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 2);
  auto all = ExactRanges(vas, plan, kAgent);
  const std::vector<core::RangeSet> only_anchor_1{all[1]};
  RelocalizationOptions los_only;
  los_only.max_order = 0;

  // Act
  const MatchScore first_order = ScorePosition(vas, plan, kAgent, only_anchor_1, RelocalizationOptions{});
  const MatchScore los = ScorePosition(vas, plan, kAgent, only_anchor_1, los_only);

  // Assert
  EXPECT_EQ(first_order.visible, 5);
  EXPECT_EQ(first_order.matched, 5);
  EXPECT_DOUBLE_EQ(first_order.fraction(), 1.0);
  EXPECT_EQ(los.visible, 1);
  EXPECT_EQ(los.matched, 1);
}

TEST(ScorePosition, IgnoresVasThatAnObstacleBlocks) {
  // Arrange: the agent stands behind the pillar as seen from anchor 0 at (1, 5): on the line
  // from the anchor through the pillar centre (2.5, 3). The LOS range is measured anyway.
  const auto plan = SquareRoomWithPillar();
  const auto vas = SquareRoomVas(plan, 1);
  const Vec2 behind(3.25, 2.0);
  const int los = IdOf(vas, 0, {});
  ASSERT_FALSE(geometry::IsVisible(vas, los, plan, behind));
  const auto visible = geometry::VisibleVirtualAnchors(vas, 0, plan, behind, 1);
  std::vector<core::RangeSet> ranges{Set(0, {{RangeTo(vas, los, behind), 1.0}})};
  for (const int id : visible) ranges[0].ranges.push_back({RangeTo(vas, id, behind), 0.5});

  // Act
  const MatchScore score = ScorePosition(vas, plan, behind, ranges, RelocalizationOptions{});

  // Assert
  EXPECT_EQ(score.visible, static_cast<int>(visible.size()));
  EXPECT_LT(score.visible, 5);
  EXPECT_EQ(score.matched, score.visible);
}

TEST(ScorePosition, GivesAZeroFractionWhenNothingIsVisible) {
  // Arrange: no measurements at all.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);

  // Act
  const MatchScore score = ScorePosition(vas, plan, kAgent, {}, RelocalizationOptions{});

  // Assert
  EXPECT_EQ(score.visible, 0);
  EXPECT_EQ(score.matched, 0);
  EXPECT_EQ(score.fraction(), 0.0);
}

TEST(SearchPosition, FindsTheTruePositionFromOneMetreAway) {
  // Arrange: exact ranges at the truth, search centred 1 m away (0.8, 0.6).
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);
  const auto ranges = ExactRanges(vas, plan, kAgent);
  const Vec2 center = kAgent + Vec2(0.8, 0.6);
  const RelocalizationOptions options;

  // Act
  const auto found = SearchPosition(vas, plan, center, ranges, options);

  // Assert: every point whose 10 expected ranges all lie within the 5 cm match tolerance ties
  // (the search keeps the first such grid point), so the result is within about the tolerance.
  ASSERT_TRUE(found.has_value());
  EXPECT_LT((*found - kAgent).norm(), options.match_tolerance_m);
  EXPECT_EQ(ScorePosition(vas, plan, *found, ranges, options).matched, 10);
}

TEST(SearchPosition, ReturnsNothingWhenTheBestScoreStaysBelowFoundScore) {
  // Arrange: one of the 10 visible VAs has no range, so the best fraction is 0.9.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);
  auto ranges = ExactRanges(vas, plan, kAgent);
  ranges[1].ranges.pop_back();
  const Vec2 center = kAgent + Vec2(-0.6, 0.8);
  RelocalizationOptions strict;
  strict.found_score = 1.0;
  RelocalizationOptions lenient;
  lenient.found_score = 0.85;

  // Act
  const auto strict_result = SearchPosition(vas, plan, center, ranges, strict);
  const auto lenient_result = SearchPosition(vas, plan, center, ranges, lenient);

  // Assert
  EXPECT_FALSE(strict_result.has_value());
  ASSERT_TRUE(lenient_result.has_value());
  EXPECT_LT((*lenient_result - kAgent).norm(), lenient.match_tolerance_m);
}

TEST(SearchPosition, ReturnsNothingForClutterOnly) {
  // Arrange: seeded uniform ranges unrelated to any position.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);
  core::Rng rng(3, 0);
  std::vector<core::RangeSet> ranges{Set(0, {}), Set(1, {})};
  for (auto& anchor : ranges) {
    for (int i = 0; i < 3; ++i) anchor.ranges.push_back({rng.Uniform(0.0, 12.0), 0.1});
  }

  // Act
  const auto found = SearchPosition(vas, plan, kAgent, ranges, RelocalizationOptions{});

  // Assert
  EXPECT_FALSE(found.has_value());
}

TEST(SearchPosition, ReturnsNothingWhenTooFewVasAreVisibleAnywhere) {
  // Arrange: at most 10 VAs are visible, min_visible asks for 11.
  const auto plan = EmptySquareRoom();
  const auto vas = SquareRoomVas(plan, 1);
  const auto ranges = ExactRanges(vas, plan, kAgent);
  RelocalizationOptions options;
  options.min_visible = 11;

  // Act
  const auto found = SearchPosition(vas, plan, kAgent, ranges, options);

  // Assert
  EXPECT_FALSE(found.has_value());
}

bool Mentions(const std::vector<std::string>& problems, const std::string& key) {
  return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) { return p.find(key) != std::string::npos; });
}

TEST(RelocalizationOptions, AcceptsTheDefaultsAndNamesEveryInvalidField) {
  const auto with = [](auto change) {
    RelocalizationOptions o;
    change(o);
    return Validate(o);
  };
  EXPECT_TRUE(Validate(RelocalizationOptions{}).empty());
  EXPECT_TRUE(Mentions(with([](auto& o) { o.match_tolerance_m = 0.0; }), "match_tolerance_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.max_order = 7; }), "max_order"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.min_visible = 0; }), "min_visible"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.lost_score = 1.5; }), "lost_score"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.lost_steps = 0; }), "lost_steps"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.search_radius_m = -1.0; }), "search_radius_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.search_step_m = 2.0; }), "search_step_m"));
  EXPECT_TRUE(Mentions(with([](auto& o) { o.found_score = -0.1; }), "found_score"));
}

TEST(RelocalizationOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(RelocalizationOptionsDescriptor(),
                                   {"enabled", "match_tolerance_m", "max_order", "min_visible", "lost_score",
                                    "lost_steps", "search_radius_m", "search_step_m", "found_score"});
}

}  // namespace
}  // namespace mirage::methods::mint
