// What the two writers share (bag_write.h).
#include "bag/bag_write.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <limits>

#include "bag/bag_io.h"
#include "bag/imu_decode.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

// sensor_msgs/Imu ends with 37 doubles: orientation (4) and its covariance
// (9), angular_velocity (3) and its covariance (9), linear_acceleration (3)
// and its covariance (9); the decoders refuse a message with bytes after
// them, so the vectors lie at these distances from its end.
constexpr std::size_t kAngularFromEnd = 8 * (3 + 9 + 3 + 9);
constexpr std::size_t kLinearFromEnd = 8 * (3 + 9);
constexpr std::size_t kAngularCovarianceFromEnd = 8 * (9 + 3 + 9);
constexpr std::size_t kLinearCovarianceFromEnd = 8 * 9;

void PutVector(std::string& data,
               std::size_t at,
               const Eigen::Vector3d& v,
               bool big_endian) {
  for (int i = 0; i < 3; ++i) {
    unsigned char raw[8];
    std::memcpy(raw, &v[i], 8);
    if (big_endian) {
      for (int k = 0; k < 4; ++k) std::swap(raw[k], raw[7 - k]);
    }
    std::memcpy(data.data() + at + 8 * static_cast<std::size_t>(i), raw, 8);
  }
}

// A row-major 3×3 covariance with `diagonal` on its diagonal, 0 elsewhere.
void PutCovariance(std::string& data,
                   std::size_t at,
                   const Eigen::Vector3d& diagonal,
                   bool big_endian) {
  for (int row = 0; row < 3; ++row) {
    Eigen::Vector3d values = Eigen::Vector3d::Zero();
    values[row] = diagonal[row];
    PutVector(data, at + 24 * static_cast<std::size_t>(row), values, big_endian);
  }
}

std::string Bz2Pack(std::string_view data) {
  // libbz2's bound: 1 % more and 600 bytes (bzlib.h, BZ2_bzBuffToBuffCompress).
  const std::uint64_t bound = data.size() + data.size() / 100 + 601;
  if (bound > std::numeric_limits<unsigned>::max())
    throw DataError("bz2: chunk too large");
  std::string out(bound, '\0');
  auto length = static_cast<unsigned>(bound);
  // Block size 9 (900 kB), as Python's bz2.BZ2Compressor that rosbag uses.
  const int rc = BZ2_bzBuffToBuffCompress(out.data(),
                                          &length,
                                          const_cast<char*>(data.data()),
                                          static_cast<unsigned>(data.size()),
                                          9,
                                          0,
                                          0);
  if (rc != BZ_OK)
    throw DataError("bz2: cannot pack (libbz2 code " + std::to_string(rc) + ")");
  out.resize(length);
  return out;
}

// The frame as roslz4 writes it (the input bags' descriptor: FLG 0x64, BD
// 0x60): independent blocks of up to 1 MB and a content checksum, which
// python3-roslz4's reader expects (it refuses a frame without one).
std::string Lz4Pack(std::string_view data) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.blockSizeID = LZ4F_max1MB;
  prefs.frameInfo.blockMode = LZ4F_blockIndependent;
  prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
  std::string out(LZ4F_compressFrameBound(data.size(), &prefs), '\0');
  const std::size_t n =
      LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &prefs);
  if (LZ4F_isError(n)) {
    throw DataError(std::string("lz4: cannot pack (") + LZ4F_getErrorName(n) + ")");
  }
  out.resize(n);
  return out;
}

std::string ZstdPack(std::string_view data) {
  std::string out(ZSTD_compressBound(data.size()), '\0');
  const std::size_t n = ZSTD_compress(
      out.data(), out.size(), data.data(), data.size(), ZSTD_CLEVEL_DEFAULT);
  if (ZSTD_isError(n)) {
    throw DataError(std::string("zstd: cannot pack (") + ZSTD_getErrorName(n) + ")");
  }
  out.resize(n);
  return out;
}

}  // namespace

std::string Compress(std::string_view compression, std::string_view data) {
  if (compression.empty() || compression == "none") return std::string(data);
  if (compression == "bz2") return Bz2Pack(data);
  if (compression == "lz4") return Lz4Pack(data);
  if (compression == "zstd") return ZstdPack(data);
  throw DataError("unknown compression '" + std::string(compression) + "'");
}

void EditImu(std::string& data,
             bool cdr,
             std::int64_t receive_ns,
             const ImuEdit& edit,
             const ImuCovariances& covariances) {
  const ImuMessage read =
      cdr ? DecodeCdrImu(data, receive_ns) : DecodeRos1Imu(data, receive_ns);
  ImuMessage edited = read;
  edit(edited);
  // CDR's second byte is 0 for big endian (DecodeCdrImu has checked it);
  // ROS 1 is little endian.
  const bool big_endian = cdr && data[1] == 0;
  if (read.has_angular_velocity) {
    PutVector(
        data, data.size() - kAngularFromEnd, edited.angular_velocity_radps, big_endian);
  }
  if (read.has_linear_acceleration) {
    PutVector(
        data, data.size() - kLinearFromEnd, edited.linear_acceleration_mps2, big_endian);
    if (covariances.linear_acceleration_m2ps4) {
      PutCovariance(data,
                    data.size() - kLinearCovarianceFromEnd,
                    *covariances.linear_acceleration_m2ps4,
                    big_endian);
    }
  }
  if (read.has_angular_velocity && covariances.angular_velocity_rad2ps2) {
    PutCovariance(data,
                  data.size() - kAngularCovarianceFromEnd,
                  *covariances.angular_velocity_rad2ps2,
                  big_endian);
  }
}

void CountingOut::Write(std::string_view bytes) {
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out_) throw Error(ErrorKind::kIo, "the recording could not be written");
  pos_ += bytes.size();
}

}  // namespace mpcal::bag
