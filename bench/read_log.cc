// The reading alone: a log or a recording read into its rows by ReadLog, the
// entry point every command reads through (for a recording: the topic
// chosen, every sensor_msgs/Imu message decoded, the rows put in time
// order), and nothing after it (no detection, no calibration).
// bench/bag_read_bench.sh runs it on the same rows as a CSV and as each
// recording format, beside the CSV's parse floor (bench/parse_floor.cc).
//
//   mpcal_read_log LOG
//
// Prints the rows read and the sum of their readings (so that nothing is
// optimised away, and the two sides can be seen to hold the same rows).
#include <cstdio>
#include <exception>

#include "mpcal/log_reader.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s LOG\n", argv[0]);
    return 2;
  }
  try {
    const mpcal::Recording rec = mpcal::ReadLog(argv[1], mpcal::LogOptions{});
    double sum = 0.0;
    for (const Eigen::Vector3d& a : rec.accel) sum += a.sum();
    for (const Eigen::Vector3d& g : rec.gyro_radps) sum += g.sum();
    std::printf("%zu rows, gyroscope %s, sum of readings %.17g\n",
                rec.accel.size(),
                rec.gyro_radps.empty() ? "no" : "yes",
                sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mpcal_read_log: %s\n", e.what());
    return 1;
  }
  return 0;
}
