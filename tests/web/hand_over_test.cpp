// A web start is handed over only while its client is there: the page's wrapped start asks the
// client named on its thread, just before the job would be registered.
#include "web/hand_over.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace cellctl::web {
namespace {

using How = plant_link::Taken::How;

struct Starts {
  int begun = 0;
  plant_link::RunAccess access() {
    plant_link::RunAccess a;
    a.start = [this](const plant_link::StartRequest&, const command::CommandSource&) {
      ++begun;
      return plant_link::Taken{How::done, "started"};
    };
    return a;
  }
};

const plant_link::StartRequest kHome = plant_link::StartHoming{};
const command::CommandSource kPage{command::CommandSource::Origin::web, "127.0.0.1:50000", "token #1"};

TEST(HandOver, AStartWhoseClientHasGoneIsNotRegistered) {
  Starts starts;
  const auto run = starts_for_present_clients(starts.access());
  bool gone = false;
  const ClientAtHandOver client([&] { return gone; });
  EXPECT_EQ(run.start(kHome, kPage).how, How::done);
  EXPECT_FALSE(client.abandoned());
  gone = true;  // the client closed while the recipe was validated
  const auto taken = run.start(kHome, kPage);
  EXPECT_EQ(taken.how, How::refused);
  EXPECT_EQ(taken.text, kClientGone);
  EXPECT_TRUE(client.abandoned());
  EXPECT_EQ(starts.begun, 1);
}

TEST(HandOver, OnlyTheClientOfThisThreadIsAsked) {
  Starts starts;
  const auto run = starts_for_present_clients(starts.access());
  EXPECT_EQ(run.start(kHome, kPage).how, How::done);  // no client named: the plant link's starts
  const ClientAtHandOver gone_client([] { return true; });
  std::thread other([&] { EXPECT_EQ(run.start(kHome, kPage).how, How::done); });
  other.join();
  EXPECT_EQ(starts.begun, 2);
}

TEST(HandOver, AnInnerClientGivesWayToTheOuterWhenItEnds) {
  Starts starts;
  const auto run = starts_for_present_clients(starts.access());
  const ClientAtHandOver outer([] { return true; });
  {
    const ClientAtHandOver inner([] { return false; });
    EXPECT_EQ(run.start(kHome, kPage).how, How::done);
  }
  EXPECT_EQ(run.start(kHome, kPage).how, How::refused);
}

TEST(HandOver, WithoutAStartThereIsNothingToWrap) {
  EXPECT_FALSE(starts_for_present_clients({}).start);  // `cellctl run` refuses starts with its reason
}

}  // namespace
}  // namespace cellctl::web
