#include "app/maps.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using Code = Status::Code;

TEST_F(AppTest, SlicesArePickedAndCachedByContent) {
  Viewer alice = User("alice"), anon;
  int64_t a = AddRoute(alice, kCrimpLadder);
  int64_t hidden = AddRoute(alice, kCrimpLadder, false);
  MapQuery q;
  q.routes = {a};
  q.grid = 9;
  q.spacing = 0.5;
  Result<std::shared_ptr<const MapSlice>> s = services_->maps.Slice(anon, q);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ((*s)->length, 6);
  EXPECT_EQ((*s)->effect.size(), 81u);
  EXPECT_EQ((*s)->effect[40], 0);  // the reference IC itself changes nothing
  EXPECT_EQ((*s)->x.size(), 9u);
  EXPECT_EQ(services_->maps.Slice(anon, q)->get(), s->get());  // cached
  MapQuery near = q;
  near.spacing = 0.5000001;  // another region: never the cached one
  EXPECT_NE(services_->maps.Slice(anon, near)->get(), s->get());
  q.routes = {hidden};
  EXPECT_EQ(services_->maps.Slice(anon, q).status().code(), Code::kNotFound);
  EXPECT_TRUE(services_->maps.Slice(alice, q).ok());

  MapQuery p;
  p.length = 20;
  p.grid = 21;
  PickQuery pick;
  pick.effect = 10;
  pick.count = 3;
  Result<std::vector<landscape::Candidate>> c = services_->maps.Pick(anon, p, pick);
  ASSERT_TRUE(c.ok()) << c.status().message();
  ASSERT_EQ(c->size(), 3u);
  EXPECT_LE((*c)[0].score, (*c)[2].score);
  pick.effect = 21;
  EXPECT_EQ(services_->maps.Pick(anon, p, pick).status().code(), Code::kInvalidInput);
}

TEST_F(AppTest, MapLimitsAreChecked) {
  Viewer anon;
  const Limits& lim = services_->options.limits;
  auto code = [&](MapQuery q) { return services_->maps.Slice(anon, q).status().code(); };
  MapQuery q;
  q.grid = lim.max_map_grid + 1;
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.spacing = -1;
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.plane = "qq";
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.length = lim.max_map_length + 1;
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.params.skip = lim.max_map_skip + 1;
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.params.mapping.kind = chaos::MappingKind::kDabby;
  EXPECT_EQ(code(q), Code::kInvalidInput);
  q = {};
  q.routes = {424242};
  EXPECT_EQ(code(q), Code::kNotFound);
}

}  // namespace
}  // namespace sb::app
