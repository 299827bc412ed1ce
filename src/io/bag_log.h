// Private to src/io: a robotics recording (bag.h: ROS 1 bag, MCAP, ROS 2 bag)
// read as a log, its sensor_msgs/Imu messages going through the same row
// sink as a text log's rows.
#pragma once

#include <functional>
#include <string>

#include "mpcal/log_reader.h"
#include "mpcal/recording.h"

namespace mpcal::logio {

/// \throws mpcal::Error (kOption) when `options` describe a text log's
///   columns, units, time unit or rate: a recording has its own.
void RefuseTextOptions(const std::string& path, const LogOptions& options);

/// ReadLog's and ReadLogRows' path for a recording: the messages are held,
/// put in time order (SortByTime), and the rows go into `*rec` (all of
/// them, or with `consume` a piece at a time) and, at the end, the warnings
/// and Recording::stamp_order.
/// \throws mpcal::Error as ReadImuMessages, for text-log options given with
///   a recording (columns, units, time unit, rate), for a recording with no
///   sensor_msgs/Imu topic or, when LogOptions::topic is empty, several; and
///   as the row sink (no rows, a time step shorter than any sensor's).
LogStreamSummary ReadBagRows(const std::string& path,
                             const LogOptions& options,
                             Recording* rec,
                             std::function<void(const Recording&)> consume);

}  // namespace mpcal::logio
