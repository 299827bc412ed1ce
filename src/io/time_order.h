// Private to src/io: a recording's rows (its messages, in file order) put in
// time order in place, and what that changed counted.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/recording.h"

namespace mpcal::logio {

/// Sorts the rows by `time` (stable: rows at one time keep their order),
/// keeps one row per time, and counts what that changed. `gyro` is empty or
/// one per row. In place: the only memory beside the rows is a permutation
/// of one index a row, and only when the rows are not in order already.
/// `time` must hold no NaN; StampOrder::worst_back_s is in its unit.
StampOrder SortByTime(std::vector<double>& time,
                      std::vector<Eigen::Vector3d>& accel,
                      std::vector<Eigen::Vector3d>& gyro);

/// "3 messages out of order (the furthest 52 ms back) put in time order;
/// 2 duplicated messages dropped; ..." after `source`; "" when nothing
/// changed.
std::string DescribeStampOrder(const StampOrder& order, const std::string& source);

}  // namespace mpcal::logio
