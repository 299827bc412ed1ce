// Private to src/bag/: what the two writers share (RewriteImuMessages in
// bag.h): the chunk compressions, a sensor_msgs/Imu edited in place, the
// little-endian encodings and an output that counts its bytes.
#pragma once

#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "mpcal/bag.h"

namespace mpcal::bag {

/// Packs `data` as `compression` says: "" or "none" (stored), "bz2", "lz4"
/// (the LZ4 frame format) or "zstd"; Decompress unpacks each.
/// \throws DataError for another compression or a library failure.
std::string Compress(std::string_view compression, std::string_view data);

/// Decodes the sensor_msgs/Imu in `data` (ROS 1 serialisation, or CDR when
/// `cdr`), hands it to `edit` and writes its two vectors back in place, in
/// the message's byte order; a vector the message marks as not measured is
/// left as it was, and so is its covariance unless `covariances` gives one.
/// \throws DataError as DecodeRos1Imu and DecodeCdrImu.
void EditImu(std::string& data,
             bool cdr,
             std::int64_t receive_ns,
             const ImuEdit& edit,
             const ImuCovariances& covariances);

/// Little-endian appends.
template <typename T>
void Put(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

/// The output with the count of bytes written, which the indexes point at.
class CountingOut {
 public:
  explicit CountingOut(std::ostream& out) : out_(out) {}
  std::uint64_t pos() const { return pos_; }
  /// \throws mpcal::Error when the stream fails.
  void Write(std::string_view bytes);

 private:
  std::ostream& out_;
  std::uint64_t pos_ = 0;
};

/// The writers of each container (ros1_writer.cc, mcap_writer.cc).
BagRewriteResult RewriteRos1(const std::string& input,
                             std::ostream& output,
                             const std::string& topic,
                             const ImuEdit& edit,
                             const ImuCovariances& covariances,
                             std::vector<std::string>& warnings);
BagRewriteResult RewriteMcap(const std::string& input,
                             std::ostream& output,
                             const std::string& topic,
                             const ImuEdit& edit,
                             const ImuCovariances& covariances,
                             std::vector<std::string>& warnings);

}  // namespace mpcal::bag
