#include "time_order.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace mpcal::logio {
namespace {

// Out of order: earlier than the latest time before it in the file.
void CountOutOfOrder(const std::vector<double>& time, StampOrder* order) {
  if (time.empty()) return;
  double latest = time.front();
  for (const double t : time) {
    if (t < latest) {
      ++order->out_of_order;
      order->worst_back_s = std::max(order->worst_back_s, latest - t);
    } else {
      latest = t;
    }
  }
}

// Applies `from` (row i of the result is row from[i]) to the three arrays by
// following its cycles, one row held aside per cycle; `from` is used up.
void Permute(std::vector<std::size_t>& from,
             std::vector<double>& time,
             std::vector<Eigen::Vector3d>& accel,
             std::vector<Eigen::Vector3d>& gyro) {
  const bool with_gyro = !gyro.empty();
  for (std::size_t start = 0; start < from.size(); ++start) {
    if (from[start] == start) continue;
    const double t = time[start];
    const Eigen::Vector3d a = accel[start];
    const Eigen::Vector3d g = with_gyro ? gyro[start] : Eigen::Vector3d::Zero();
    std::size_t at = start;
    while (from[at] != start) {
      const std::size_t next = from[at];
      time[at] = time[next];
      accel[at] = accel[next];
      if (with_gyro) gyro[at] = gyro[next];
      from[at] = at;
      at = next;
    }
    time[at] = t;
    accel[at] = a;
    if (with_gyro) gyro[at] = g;
    from[at] = at;
  }
}

// One row per time, the first (in file order, the sort being stable). A
// second message at one time is either the same message recorded twice
// (dropping it loses nothing) or another sample stamped with the same time
// (a driver that stamps a burst read from the sensor's FIFO at once). Both
// cannot be kept: every estimator takes the rows at strictly increasing
// times (rates, windows, the turns' integration). Averaging them would make
// a row with half the noise variance of the others, which the Allan
// deviation and the positions' noise weights would read as a quieter
// sensor; dropping it loses one sample of noise and keeps every row a
// reading as the sensor made it.
void KeepOnePerTime(std::vector<double>& time,
                    std::vector<Eigen::Vector3d>& accel,
                    std::vector<Eigen::Vector3d>& gyro,
                    StampOrder* order) {
  const bool with_gyro = !gyro.empty();
  std::size_t kept = 0;
  std::size_t first_at_time = 0;  // the kept row of the current time
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (kept > 0 && time[i] == time[kept - 1]) {
      const bool same = accel[i] == accel[first_at_time] &&
                        (!with_gyro || gyro[i] == gyro[first_at_time]);
      ++(same ? order->duplicated : order->same_time_other_readings);
      continue;
    }
    if (kept != i) {
      time[kept] = time[i];
      accel[kept] = accel[i];
      if (with_gyro) gyro[kept] = gyro[i];
    }
    first_at_time = kept++;
  }
  time.resize(kept);
  accel.resize(kept);
  if (with_gyro) gyro.resize(kept);
}

}  // namespace

StampOrder SortByTime(std::vector<double>& time,
                      std::vector<Eigen::Vector3d>& accel,
                      std::vector<Eigen::Vector3d>& gyro) {
  StampOrder order;
  CountOutOfOrder(time, &order);
  if (order.out_of_order > 0) {
    std::vector<std::size_t> from(time.size());
    std::iota(from.begin(), from.end(), std::size_t{0});
    std::stable_sort(from.begin(), from.end(), [&time](std::size_t a, std::size_t b) {
      return time[a] < time[b];
    });
    Permute(from, time, accel, gyro);
  }
  KeepOnePerTime(time, accel, gyro, &order);
  return order;
}

std::string DescribeStampOrder(const StampOrder& order, const std::string& source) {
  if (!order.changed()) return "";
  std::string out;
  auto add = [&out](const std::string& part) { out += (out.empty() ? "" : "; ") + part; };
  auto messages = [](std::size_t n) {
    return fmt::format("{} message{}", n, n == 1 ? "" : "s");
  };
  if (order.out_of_order > 0) {
    add(fmt::format("{} out of order (the furthest {:.4g} ms back) put in time order",
                    messages(order.out_of_order),
                    order.worst_back_s * 1e3));
  }
  if (order.duplicated > 0) {
    add(fmt::format("{} recorded twice (same time and readings) dropped",
                    messages(order.duplicated)));
  }
  if (order.same_time_other_readings > 0) {
    add(fmt::format(
        "{} at the time of an earlier one with other readings dropped (the first kept)",
        messages(order.same_time_other_readings)));
  }
  return source + ": " + out;
}

}  // namespace mpcal::logio
