// libFuzzer target for the ROS 2 SQLite bag reader. What mpcal does with such
// a file is its own code over SQLite's rows: the topics table's type and
// serialisation format checked, the topic's messages selected, each CDR blob
// decoded. The SQLite file format itself is SQLite's parser, fuzzed by its
// authors; mutated database pages would mostly stop at "file is not a
// database" and never reach mpcal's code. So the input is the rows: split at
// kSeparator, its first part is the /imu/data topic's "type format" and each
// further part one message's data. The target builds the database as ros2's
// rosbag2_storage_sqlite3 lays it out (the tables of
// tests/data/bags/make_ros2_db3.py, with a /chatter topic beside), in memory,
// writes its bytes to an in-memory file and reads that as a bag.
#include <sqlite3.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "bag_input.h"

namespace {

constexpr std::string_view kSeparator = "\n#msg\n";
constexpr std::int64_t kFirstNs = 1'700'000'000'000'000'000;
constexpr std::int64_t kStepNs = 2'500'000;  // 400 Hz

void Must(int rc, sqlite3* db, const char* what) {
  if (rc != SQLITE_OK && rc != SQLITE_DONE) {
    std::fprintf(stderr, "ros2_bag_fuzzer: %s: %s\n", what, sqlite3_errmsg(db));
    std::abort();
  }
}

std::vector<std::string_view> Parts(std::string_view input) {
  std::vector<std::string_view> parts;
  for (;;) {
    const std::size_t at = input.find(kSeparator);
    parts.push_back(input.substr(0, at));
    if (at == std::string_view::npos) return parts;
    input.remove_prefix(at + kSeparator.size());
  }
}

// The database with the topics and messages of `parts`, as its file's bytes.
std::string Database(const std::vector<std::string_view>& parts) {
  sqlite3* db = nullptr;
  Must(sqlite3_open(":memory:", &db), db, "open");
  Must(sqlite3_exec(db,
                    "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, "
                    "ros_distro TEXT NOT NULL);"
                    "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, "
                    "type TEXT NOT NULL, serialization_format TEXT NOT NULL, "
                    "offered_qos_profiles TEXT NOT NULL, type_description_hash TEXT NOT "
                    "NULL);"
                    "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT "
                    "NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
                    "INSERT INTO schema VALUES (4, 'jazzy');"
                    "INSERT INTO topics VALUES (1, '/chatter', 'std_msgs/msg/String', "
                    "'cdr', '', '');"
                    "BEGIN;",
                    nullptr,
                    nullptr,
                    nullptr),
       db,
       "create");
  const std::string_view topic = parts.front();
  const std::size_t space = topic.find(' ');
  const std::string type(topic.substr(0, space));
  const std::string format(space == std::string_view::npos ? std::string_view()
                                                           : topic.substr(space + 1));
  sqlite3_stmt* s = nullptr;
  Must(sqlite3_prepare_v2(db,
                          "INSERT INTO topics VALUES (2, '/imu/data', ?, ?, '', '')",
                          -1,
                          &s,
                          nullptr),
       db,
       "prepare");
  sqlite3_bind_text(s, 1, type.data(), static_cast<int>(type.size()), SQLITE_TRANSIENT);
  sqlite3_bind_text(
      s, 2, format.data(), static_cast<int>(format.size()), SQLITE_TRANSIENT);
  Must(sqlite3_step(s), db, "insert topic");
  sqlite3_finalize(s);
  Must(sqlite3_prepare_v2(
           db,
           "INSERT INTO messages(topic_id, timestamp, data) VALUES (?, ?, ?)",
           -1,
           &s,
           nullptr),
       db,
       "prepare");
  for (std::size_t i = 1; i < parts.size(); ++i) {
    // Every fourth row goes to /chatter, which the reader must leave alone.
    sqlite3_bind_int64(s, 1, i % 4 == 0 ? 1 : 2);
    sqlite3_bind_int64(s, 2, kFirstNs + static_cast<std::int64_t>(i) * kStepNs);
    sqlite3_bind_blob(
        s, 3, parts[i].data(), static_cast<int>(parts[i].size()), SQLITE_TRANSIENT);
    Must(sqlite3_step(s), db, "insert message");
    sqlite3_reset(s);
  }
  sqlite3_finalize(s);
  Must(sqlite3_exec(db, "COMMIT;", nullptr, nullptr, nullptr), db, "commit");
  sqlite3_int64 size = 0;
  unsigned char* bytes = sqlite3_serialize(db, "main", &size, 0);
  if (bytes == nullptr) {
    std::fprintf(stderr, "ros2_bag_fuzzer: the database cannot be serialised\n");
    std::abort();
  }
  std::string file(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(size));
  sqlite3_free(bytes);
  sqlite3_close(db);
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string_view> parts =
      Parts(std::string_view(reinterpret_cast<const char*>(data), size));
  const std::string file = Database(parts);
  const std::string path = mpcal::fuzz::WriteMemoryFile(file.data(), file.size());
  // One message at most from each /imu/data row.
  mpcal::fuzz::ReadBagChecked(path, parts.size() - 1);
  return 0;
}
