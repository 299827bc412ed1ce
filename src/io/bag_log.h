// Private to src/io: a robotics recording (bag.h: ROS 1 bag, MCAP, ROS 2 bag)
// read as a log, its sensor_msgs/Imu messages going through the same row
// sink as a text log's rows.
#pragma once

#include <functional>
#include <string>

#include "mpcal/log_reader.h"
#include "mpcal/recording.h"

namespace mpcal::logio {

/// ReadLog's and ReadLogRows' path for a recording: the rows go into `*rec`
/// (all of them, or with `consume` each batch's in turn) and, at the end,
/// the warnings, as for a text log.
/// \throws mpcal::Error as ReadImuMessages, for text-log options given with
///   a recording (columns, units, time unit, rate), for a recording with no
///   sensor_msgs/Imu topic or, when LogOptions::topic is empty, several; and
///   as the row sink (time going back, no rows).
LogStreamSummary ReadBagRows(const std::string& path,
                             const LogOptions& options,
                             Recording* rec,
                             std::function<void(const Recording&)> consume);

}  // namespace mpcal::logio
