// ROS 2 bags in SQLite: the tables `topics(id, name, type,
// serialization_format, ...)` and `messages(id, topic_id, timestamp, data)`
// as ros2/rosbag2's rosbag2_storage_sqlite3 creates them
// (rosbag2_storage_sqlite3/src/rosbag2_storage_sqlite3/sqlite_storage.cpp at
// commit 25304dd36e51cc0fbccf148fded2dd4ba5ccba35: SqliteStorage::initialize,
// lines 434-480, the tables at 447-469; messages written at 542 with their
// receive timestamp in ns). The messages are CDR (imu_decode.h). SQLite
// stays inside this file; the database is opened read-only and immutable, so
// a bag being recorded is never written to.
#include "bag/ros2_bag.h"

#include <sqlite3.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include "bag/bag_io.h"
#include "bag/imu_decode.h"
#include "bag/mcap_bag.h"
#include "bag/ros1_bag.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

namespace fs = std::filesystem;

// The number after the last '_' of a storage file's stem ("bag_12.db3").
long SplitNumber(const fs::path& p) {
  const std::string stem = p.stem().string();
  const std::size_t underscore = stem.rfind('_');
  if (underscore == std::string::npos) return -1;
  try {
    return std::stol(stem.substr(underscore + 1));
  } catch (const std::exception&) {
    return -1;
  }
}

class Database {
 public:
  explicit Database(const std::string& path) : path_(path) {
    const std::string uri = "file:" + path + "?immutable=1";
    sqlite3* db = nullptr;
    const int rc =
        sqlite3_open_v2(uri.c_str(),
                        &db,
                        // One thread uses the connection: no mutex around each call,
                        // which a step per message would otherwise lock and unlock.
                        SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX,
                        nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) Fail("cannot be opened as SQLite");
  }
  [[noreturn]] void Fail(const std::string& what) const {
    throw Error(ErrorKind::kInput,
                path_ + ": " + what + " (" +
                    (db_ ? sqlite3_errmsg(db_.get()) : "no memory") + ")");
  }
  sqlite3_stmt* Prepare(const char* sql) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql, -1, &s, nullptr) != SQLITE_OK) {
      sqlite3_finalize(s);
      Fail("is not a ROS 2 bag database (no topics and messages tables)");
    }
    return s;
  }
  // Steps `s`; false at its end.
  bool Step(sqlite3_stmt* s) {
    const int rc = sqlite3_step(s);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    Fail("cannot be read");
  }

 private:
  struct Close {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  std::string path_;
  std::unique_ptr<sqlite3, Close> db_;
};

using Statement = std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)>;

std::string Text(sqlite3_stmt* s, int column) {
  const unsigned char* t = sqlite3_column_text(s, column);
  return t ? std::string(reinterpret_cast<const char*>(t)) : std::string();
}

struct Ros2Topic {
  std::int64_t id = 0;
  BagTopic topic;
};

std::vector<Ros2Topic> Topics(Database& db) {
  Statement s(
      db.Prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id"),
      sqlite3_finalize);
  std::vector<Ros2Topic> topics;
  while (db.Step(s.get())) {
    topics.push_back({sqlite3_column_int64(s.get(), 0),
                      {Text(s.get(), 1), Text(s.get(), 2), Text(s.get(), 3), 0, 0, 0}});
  }
  return topics;
}

bool IsMcap(const std::string& file) { return fs::path(file).extension() == ".mcap"; }

void Merge(BagTopic& into, const BagTopic& part) {
  if (part.messages <= 0) return;
  into.first_ns =
      into.messages == 0 ? part.first_ns : std::min(into.first_ns, part.first_ns);
  into.last_ns = into.messages == 0 ? part.last_ns : std::max(into.last_ns, part.last_ns);
  into.messages += part.messages;
}

// Each topic's messages and first and last timestamps.
void CountMessages(Database& db, std::vector<Ros2Topic>& topics) {
  // Counted here over one pass of the table: rosbag2 indexes the messages
  // by timestamp, not by topic, so SQLite's GROUP BY topic_id would first
  // sort every row (three times the pass on a million messages).
  Statement s(db.Prepare("SELECT topic_id, timestamp FROM messages"), sqlite3_finalize);
  std::map<std::int64_t, BagTopic> counted;
  while (db.Step(s.get())) {
    BagTopic& c = counted[sqlite3_column_int64(s.get(), 0)];
    const std::int64_t t = sqlite3_column_int64(s.get(), 1);
    c.first_ns = c.messages == 0 ? t : std::min(c.first_ns, t);
    c.last_ns = c.messages == 0 ? t : std::max(c.last_ns, t);
    ++c.messages;
  }
  for (Ros2Topic& t : topics) {
    const auto it = counted.find(t.id);
    if (it == counted.end()) continue;
    t.topic.messages = it->second.messages;
    t.topic.first_ns = it->second.first_ns;
    t.topic.last_ns = it->second.last_ns;
  }
}

void InspectDb3(const std::string& file, bool count_messages, BagSummary& summary) {
  Database db(file);
  std::vector<Ros2Topic> topics = Topics(db);
  if (count_messages) CountMessages(db, topics);
  for (const Ros2Topic& t : topics) {
    auto it = std::find_if(summary.topics.begin(),
                           summary.topics.end(),
                           [&](const BagTopic& b) { return b.name == t.topic.name; });
    if (it == summary.topics.end()) {
      summary.topics.push_back(t.topic);
    } else {
      Merge(*it, t.topic);
    }
  }
}

// Returns false when the file has no such topic.
bool ReadDb3(const std::string& file,
             const std::string& topic,
             ImuBatcher& batcher,
             std::vector<BagTopic>& seen) {
  Database db(file);
  const std::vector<Ros2Topic> topics = Topics(db);
  const Ros2Topic* wanted = nullptr;
  for (const Ros2Topic& t : topics) {
    seen.push_back(t.topic);
    if (t.topic.name == topic) wanted = &t;
  }
  if (wanted == nullptr) return false;
  if (wanted->topic.type != kRos2ImuType || wanted->topic.encoding != "cdr") {
    throw Error(ErrorKind::kInput,
                file + ": topic '" + topic + "' holds " + wanted->topic.type + " in '" +
                    wanted->topic.encoding + "', not sensor_msgs/msg/Imu in 'cdr'");
  }
  Statement s(db.Prepare("SELECT id, timestamp, data FROM messages WHERE topic_id = ? "
                         "ORDER BY id"),
              sqlite3_finalize);
  sqlite3_bind_int64(s.get(), 1, wanted->id);
  while (db.Step(s.get())) {
    const auto* data = static_cast<const char*>(sqlite3_column_blob(s.get(), 2));
    const int size = sqlite3_column_bytes(s.get(), 2);
    try {
      batcher.Add(DecodeCdrImu(std::string_view(data ? data : "", data ? size : 0),
                               sqlite3_column_int64(s.get(), 1)));
    } catch (const DataError& e) {
      throw Error(ErrorKind::kInput,
                  file + ": message id " +
                      std::to_string(sqlite3_column_int64(s.get(), 0)) + ": " + e.what());
    }
  }
  return true;
}

}  // namespace

std::vector<std::string> Ros2StorageFiles(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return {path};
  std::vector<fs::path> db3, mcap;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    if (entry.path().extension() == ".db3") db3.push_back(entry.path());
    if (entry.path().extension() == ".mcap") mcap.push_back(entry.path());
  }
  std::vector<fs::path>& files = db3.empty() ? mcap : db3;
  if (files.empty()) {
    throw Error(ErrorKind::kInput,
                path + ": a ROS 2 bag directory with no *.db3 or *.mcap file");
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return std::pair(SplitNumber(a), a.string()) < std::pair(SplitNumber(b), b.string());
  });
  return {files.begin(), files.end()};
}

BagSummary InspectRos2(const std::string& path, bool count_messages) {
  BagSummary summary;
  summary.format = BagFormat::kRos2Sqlite;
  for (const std::string& file : Ros2StorageFiles(path)) {
    if (!IsMcap(file)) {
      InspectDb3(file, count_messages, summary);
      continue;
    }
    const BagSummary part = InspectMcap(file);
    for (const BagTopic& t : part.topics) {
      auto it = std::find_if(summary.topics.begin(),
                             summary.topics.end(),
                             [&](const BagTopic& b) { return b.name == t.name; });
      if (it == summary.topics.end())
        summary.topics.push_back(t);
      else
        Merge(*it, t);
    }
    summary.warnings.insert(
        summary.warnings.end(), part.warnings.begin(), part.warnings.end());
    summary.compressions.insert(
        summary.compressions.end(), part.compressions.begin(), part.compressions.end());
  }
  std::sort(summary.compressions.begin(), summary.compressions.end());
  summary.compressions.erase(
      std::unique(summary.compressions.begin(), summary.compressions.end()),
      summary.compressions.end());
  return summary;
}

void ReadRos2Imu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings) {
  ImuBatcher batcher(sink);
  std::vector<BagTopic> seen;
  bool found = false;
  for (const std::string& file : Ros2StorageFiles(path)) {
    if (IsMcap(file)) {
      batcher.Flush();
      ReadMcapImu(file, topic, sink, warnings);
      found = true;
      continue;
    }
    found = ReadDb3(file, topic, batcher, seen) || found;
  }
  batcher.Flush();
  if (!found) {
    throw Error(ErrorKind::kInput,
                path + ": no topic '" + topic + "'; the bag holds " + ListTopics(seen));
  }
  if (batcher.count() == 0 && !IsMcap(Ros2StorageFiles(path).front())) {
    warnings.push_back(path + ": topic '" + topic + "' holds no message");
  }
}

}  // namespace mpcal::bag
