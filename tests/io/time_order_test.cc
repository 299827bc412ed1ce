// A recording's rows put in time order in place: the rows follow their
// times, one is kept per time (the first in the file), and what changed is
// counted as the definitions in recording.h say.
#include "io/time_order.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mpcal::logio {
namespace {

Eigen::Vector3d A(double x) { return {x, 2 * x, 3 * x}; }
Eigen::Vector3d G(double x) { return {-x, 0.5 * x, 7.0}; }

struct Rows {
  std::vector<double> time;
  std::vector<Eigen::Vector3d> accel;
  std::vector<Eigen::Vector3d> gyro;
  // A row whose readings are made from `reading`, so that a test can tell
  // which row ended where.
  void Add(double t, double reading) {
    time.push_back(t);
    accel.push_back(A(reading));
    gyro.push_back(G(reading));
  }
};

TEST(SortByTime, RowsInOrderAreLeftAsTheyAre) {
  Rows r;
  for (int i = 0; i < 5; ++i) r.Add(i * 0.01, i);
  const Rows before = r;
  const StampOrder order = SortByTime(r.time, r.accel, r.gyro);
  EXPECT_FALSE(order.changed());
  EXPECT_EQ(r.time, before.time);
  EXPECT_EQ(r.accel, before.accel);
  EXPECT_EQ(r.gyro, before.gyro);
  EXPECT_EQ(DescribeStampOrder(order, "a.bag"), "");
}

// File order 0, 3, 1, 2, 6, 4, 5 (readings made from the times): 1 and 2
// are earlier than 3, 4 and 5 than 6; the furthest back is 1 after 3 (and 4
// after 6): 2 s.
TEST(SortByTime, RowsFollowTheirTimesAndTheLateOnesAreCounted) {
  Rows r;
  for (const double t : {0.0, 3.0, 1.0, 2.0, 6.0, 4.0, 5.0}) r.Add(t, t);
  const StampOrder order = SortByTime(r.time, r.accel, r.gyro);
  EXPECT_EQ(order.out_of_order, 4u);
  EXPECT_DOUBLE_EQ(order.worst_back_s, 2.0);
  EXPECT_EQ(order.duplicated, 0u);
  EXPECT_EQ(order.same_time_other_readings, 0u);
  ASSERT_EQ(r.time.size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    const double t = static_cast<double>(i);
    EXPECT_EQ(r.time[i], t);
    EXPECT_EQ(r.accel[i], A(t));
    EXPECT_EQ(r.gyro[i], G(t));
  }
}

// At t = 2 the first message in the file is kept; a copy of it is dropped
// as duplicated, a message with other readings is dropped and counted
// apart; a late copy is both out of order and duplicated.
TEST(SortByTime, OneRowPerTimeTheFirstInTheFile) {
  Rows r;
  r.Add(0.0, 10);
  r.Add(2.0, 20);  // first at t = 2: kept
  r.Add(1.0, 11);  // out of order
  r.Add(2.0, 20);  // the same message again: duplicated
  r.Add(2.0, 21);  // other readings at t = 2: dropped, counted apart
  r.Add(3.0, 30);
  r.Add(1.0, 11);  // a late copy: out of order and duplicated
  const StampOrder order = SortByTime(r.time, r.accel, r.gyro);
  EXPECT_EQ(order.out_of_order, 2u);
  EXPECT_DOUBLE_EQ(order.worst_back_s, 2.0);
  EXPECT_EQ(order.duplicated, 2u);
  EXPECT_EQ(order.same_time_other_readings, 1u);
  const std::vector<double> times{0.0, 1.0, 2.0, 3.0};
  EXPECT_EQ(r.time, times);
  const std::vector<Eigen::Vector3d> accel{A(10), A(11), A(20), A(30)};
  EXPECT_EQ(r.accel, accel);
  const std::vector<Eigen::Vector3d> gyro{G(10), G(11), G(20), G(30)};
  EXPECT_EQ(r.gyro, gyro);
  EXPECT_EQ(DescribeStampOrder(order, "a.bag"),
            "a.bag: 2 messages out of order (the furthest 2000 ms back) put in time "
            "order; 2 messages recorded twice (same time and readings) dropped; 1 "
            "message at the time of an earlier one with other readings dropped (the "
            "first kept)");
}

// The same readings in the accelerometer but not the gyroscope are other
// readings; without a gyroscope, the accelerometer alone decides.
TEST(SortByTime, TheGyroscopeCountsInTheComparisonWhenThereIsOne) {
  Rows r;
  r.Add(0.0, 1);
  r.Add(0.0, 1);
  r.gyro.back().x() += 1e-12;
  Rows no_gyro = r;
  no_gyro.gyro.clear();
  const StampOrder with = SortByTime(r.time, r.accel, r.gyro);
  EXPECT_EQ(with.same_time_other_readings, 1u);
  EXPECT_EQ(with.duplicated, 0u);
  const StampOrder without = SortByTime(no_gyro.time, no_gyro.accel, no_gyro.gyro);
  EXPECT_EQ(without.duplicated, 1u);
  EXPECT_TRUE(no_gyro.gyro.empty());
  EXPECT_EQ(no_gyro.time.size(), 1u);
}

// A long series reversed in pieces: the cycles of the permutation are
// followed whole, every row lands at its time.
TEST(SortByTime, ALongShuffledSeriesIsSortedWhole) {
  Rows r;
  const int n = 10000;
  for (int block = 0; block < n / 100; ++block) {
    for (int k = 99; k >= 0; --k) r.Add(block * 100 + k, block * 100 + k);
  }
  const StampOrder order = SortByTime(r.time, r.accel, r.gyro);
  EXPECT_EQ(order.out_of_order, static_cast<std::size_t>(n - n / 100));
  EXPECT_DOUBLE_EQ(order.worst_back_s, 99.0);
  ASSERT_EQ(r.time.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(r.time[i], i);
    ASSERT_EQ(r.accel[i], A(i));
    ASSERT_EQ(r.gyro[i], G(i));
  }
}

}  // namespace
}  // namespace mpcal::logio
