/// \file bag.h
/// \brief Robotics recordings read without ROS: ROS 1 bags (format 2.0), MCAP
/// files and ROS 2 bags stored in SQLite (a directory with metadata.yaml and
/// *.db3), and the sensor_msgs/Imu messages of one topic in them.
///
/// The readers check every length against what remains of the file (or of
/// the decompressed chunk) and against the caps below, so a damaged or
/// hostile file is refused with an mpcal::Error naming the file, the record
/// or byte offset and what was wrong; it never makes them read without bound.
/// Messages are handed over a batch at a time in file order, so memory stays
/// at a few chunks whatever the recording's length.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace mpcal {

/// The container a recording is stored in.
enum class BagFormat {
  kRos1,        ///< ROS 1 bag, format 2.0 (`#ROSBAG V2.0`)
  kMcap,        ///< MCAP (`\x89MCAP0\r\n`), ROS 1 or ROS 2 (CDR) messages
  kRos2Sqlite,  ///< ROS 2 bag: a directory with metadata.yaml and its *.db3
                ///< files (or *.mcap files), or a lone *.db3 file
};
/// "ros1", "mcap" or "ros2-sqlite".
std::string_view ToString(BagFormat format);

/// One topic (ROS 1: all connections of one topic; MCAP: a channel).
struct BagTopic {
  std::string name;
  /// Message type as the file names it ("sensor_msgs/Imu",
  /// "sensor_msgs/msg/Imu").
  std::string type;
  /// Serialisation of the messages: "ros1" or "cdr".
  std::string encoding;
  /// Messages on the topic: from the index where the file has one (ROS 1
  /// index data records, MCAP message indexes), else counted by reading.
  std::int64_t messages = 0;
  /// Receive (log) time of the first and last message, ns since the Unix
  /// epoch; 0 when unknown.
  std::int64_t first_ns = 0;
  std::int64_t last_ns = 0;
};

/// What InspectBag found.
struct BagSummary {
  BagFormat format = BagFormat::kRos1;
  std::vector<BagTopic> topics;
  /// Chunk compressions found ("none", "bz2", "lz4", "zstd"), each once.
  std::vector<std::string> compressions;
  /// Conditions that did not stop the reading (no index, a file cut short).
  std::vector<std::string> warnings;
};

/// One sensor_msgs/Imu message, in SI units as ROS defines them.
struct ImuMessage {
  /// The message's header stamp, ns since the Unix epoch.
  std::int64_t stamp_ns = 0;
  /// When the recorder received it (ROS 1 record time, MCAP log_time, ROS 2
  /// timestamp), ns since the Unix epoch.
  std::int64_t receive_ns = 0;
  Eigen::Vector3d linear_acceleration_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
  /// False when the message says the quantity is not measured: the first
  /// element of its covariance is -1, as sensor_msgs/Imu's definition asks
  /// of drivers; the vector is then whatever the driver left there.
  bool has_linear_acceleration = true;
  bool has_angular_velocity = true;
};

/// Receives the messages, a batch at a time in file order. The span is valid
/// only during the call.
using ImuSink = std::function<void(std::span<const ImuMessage>)>;

/// Caps every reader enforces, whatever a length field says.
inline constexpr std::uint64_t kBagMaxChunkBytes = 512ull << 20;  ///< a chunk, unpacked
inline constexpr std::uint64_t kBagMaxRecordBytes = 64ull << 20;  ///< any other record
inline constexpr std::uint64_t kBagMaxFieldBytes = 1ull << 20;    ///< a header, a name

/// The format of `path` from its first bytes; a directory holding
/// metadata.yaml is a ROS 2 bag.
/// \throws mpcal::Error when `path` cannot be opened or is none of the formats
///   (the message names the magic bytes found).
BagFormat DetectBagFormat(const std::string& path);

/// True when DetectBagFormat would name a format for `path`; false for
/// anything else (a text log, standard input "-", a missing file). Never
/// throws.
bool IsBag(const std::string& path);

/// The topics of a recording, with their types and message counts, from its
/// index (ROS 1 connection and chunk-info records, MCAP summary section) or,
/// where there is none, from one pass over the records.
/// \throws mpcal::Error for a file that DetectBagFormat refuses, or a record
///   that cannot be read (naming the file, the record and its byte offset).
BagSummary InspectBag(const std::string& path);

/// The topics of a recording as InspectBag lists them, with the message
/// counts and times its index holds; a ROS 2 bag's SQLite files have none,
/// and their topics come from the topics table alone (messages, first_ns and
/// last_ns 0), without InspectBag's pass over every message.
/// \throws mpcal::Error as InspectBag.
std::vector<BagTopic> ListBagTopics(const std::string& path);

/// Decodes every sensor_msgs/Imu message on `topic` and hands them to `sink`
/// in file order. Conditions that do not stop the reading (no index, a file
/// cut short, a topic with no message) are appended to `warnings`.
/// \throws mpcal::Error naming the file and the topic when the topic is
///   absent or of another type (or its ROS 1 md5sum differs from
///   sensor_msgs/Imu's), and naming the record or byte offset for a corrupt
///   record or chunk, an unknown compression or message encoding, a CRC that
///   does not match, or a message whose length does not fit sensor_msgs/Imu.
///   Exceptions thrown by `sink` pass through.
void ReadImuMessages(const std::string& path,
                     const std::string& topic,
                     const ImuSink& sink,
                     std::vector<std::string>& warnings);

/// Changes one message's two vectors (linear_acceleration_mps2,
/// angular_velocity_radps); whatever else it changes is not written.
using ImuEdit = std::function<void(ImuMessage&)>;

/// Covariance diagonals RewriteImuMessages writes into each message it
/// edits, for each vector the message measures (the 3×3 covariance's other
/// elements set to 0); empty: the message's own kept.
struct ImuCovariances {
  std::optional<Eigen::Vector3d> linear_acceleration_m2ps4;
  std::optional<Eigen::Vector3d> angular_velocity_rad2ps2;
};

/// What RewriteImuMessages wrote.
struct BagRewriteResult {
  BagFormat format = BagFormat::kRos1;
  /// sensor_msgs/Imu messages of the topic, each passed to the edit.
  std::int64_t imu_messages = 0;
  /// Messages of every other topic, copied as they were.
  std::int64_t other_messages = 0;
  /// Chunk compressions written (each chunk keeps its own), each once.
  std::vector<std::string> compressions;
};

/// Copies the recording at `input` (a ROS 1 bag or an MCAP file) into
/// `output` as a recording of the same kind: every record of another topic and every
/// connection, schema and channel record byte for byte, each chunk with its own
/// compression, the index (ROS 1 index data and chunk info records, MCAP
/// message indexes and summary) made afresh for the file written. Each
/// sensor_msgs/Imu message on `topic` is decoded, given to `edit`, and its two
/// vectors written back in place in the message's own serialisation (ROS 1
/// or CDR, its byte order), with the covariance diagonals `covariances`
/// gives; its header, orientation and the other covariances stay as they
/// were. A vector the message marks as not measured
/// (covariance starting with −1) is written back unchanged. Memory is a few
/// chunks and one small entry per chunk, whatever the recording's length.
/// ROS 1 bags are written as Debian's rosbag (bag.py) writes them: the bag
/// header record completed at the end, so `output` must seek (a file, as
/// WriteStreamAtomically gives it).
/// \throws mpcal::Error as ReadImuMessages for the input, for a ROS 2 bag
///   (not written), and for an output that does not seek or fails. Bytes
///   may have been written before a throw: give a stream whose file is
///   dropped then (WriteStreamAtomically). Exceptions thrown by `edit` pass
///   through.
BagRewriteResult RewriteImuMessages(const std::string& input,
                                    std::ostream& output,
                                    const std::string& topic,
                                    const ImuEdit& edit,
                                    std::vector<std::string>& warnings,
                                    const ImuCovariances& covariances = {});

}  // namespace mpcal
