// SPDX-License-Identifier: BSD-3-Clause
// rosbag2's SQLite storage through Debian's libsqlite3, read-only. Only the columns every rosbag2
// release has are read (topics: id, name, type, serialization_format; messages: id, topic_id,
// timestamp, data), so the schema/metadata tables and the type_description_hash column of newer
// releases (Iron, Jazzy) are simply not looked at. BagError's offset is a message's row id here
// (its message says "message id N"), or 0 for the database as a whole.

#include "sonargrid/io/bag/rosbag2_sqlite.h"

#include <sqlite3.h>

#include <algorithm>
#include <climits>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "sonargrid/io/log_options.h"

namespace sg::bag {
namespace {

constexpr std::uint64_t kRowsPerStep = 1000;

struct DbClose {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
struct StmtFinalize {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Db = std::unique_ptr<sqlite3, DbClose>;
using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinalize>;

std::string text(sqlite3_stmt* s, int column) {
  const unsigned char* t = sqlite3_column_text(s, column);
  if (t == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(t),
                     static_cast<std::size_t>(sqlite3_column_bytes(s, column)));
}

class SqliteReader final : public Reader {
 public:
  SqliteReader(Db db, std::string name) : db_(std::move(db)), name_(std::move(name)) { open(); }

  const std::vector<Topic>& topics() const override { return topics_; }
  const Skipped& skipped() const override { return skipped_; }

  void read(const std::vector<bool>& wanted, const ReadOptions& options,
            const std::function<void(const Message&)>& visit) override {
    skipped_ = {};
    if (orphans_ != 0) {
      problem(error(orphanRow_, "message id " + std::to_string(orphanRow_) + ": topic_id " +
                                    std::to_string(orphanTopic_) + " is not in the topics table (" +
                                    std::to_string(orphans_) + " such messages)"),
              options);
      skipped_.count += orphans_ - 1;  // every such message is left out
    }
    std::string ids;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < topics_.size() && i < wanted.size(); ++i) {
      if (!wanted[i]) continue;
      ids += (ids.empty() ? "" : ",") + std::to_string(topicIds_[i]);
      total += topics_[i].count;
    }
    if (ids.empty()) return;
    Stmt s = prepare("SELECT id, topic_id, timestamp, data FROM messages WHERE topic_id IN (" +
                     ids + ") ORDER BY timestamp, id");
    std::map<std::int64_t, std::size_t> index;
    for (std::size_t i = 0; i < topics_.size(); ++i) index[topicIds_[i]] = i;
    std::uint64_t rows = 0;
    std::int64_t last = 0;
    while (true) {
      const int rc = sqlite3_step(s.get());
      if (rc == SQLITE_DONE) break;
      if (rc != SQLITE_ROW) {
        // The statement cannot go on after an error: a lenient read counts it and stops.
        problem(error(static_cast<std::uint64_t>(last),
                      (rows == 0 ? std::string("reading the messages")
                                 : "after message id " + std::to_string(last)) +
                          ": SQLite error: " + sqlite3_errmsg(db_.get())),
                options);
        break;
      }
      const std::int64_t id = sqlite3_column_int64(s.get(), 0);
      last = id;
      const auto topic = index.find(sqlite3_column_int64(s.get(), 1));
      const std::string& topicName = topic != index.end() ? topics_[topic->second].name : name_;
      if (topic == index.end()) {  // cannot happen with the WHERE clause; kept for safety
        problem(error(static_cast<std::uint64_t>(id),
                      "message id " + std::to_string(id) + ": topic_id not asked for"),
                options);
      } else if (sqlite3_column_type(s.get(), 3) != SQLITE_BLOB &&
                 sqlite3_column_type(s.get(), 3) != SQLITE_TEXT) {
        problem(BagError(name_, static_cast<std::uint64_t>(id), topicName,
                         "message id " + std::to_string(id) + ": its data are not a BLOB"),
                options);
      } else {
        Message m;
        m.topic = topic->second;
        m.logTimeNs = sqlite3_column_int64(s.get(), 2);
        const void* blob = sqlite3_column_blob(s.get(), 3);
        const int bytes = sqlite3_column_bytes(s.get(), 3);
        if (blob != nullptr && bytes > 0) {
          m.data =
              std::string_view(static_cast<const char*>(blob), static_cast<std::size_t>(bytes));
        }
        m.offset = static_cast<std::uint64_t>(id);
        visit(m);
      }
      if (++rows % kRowsPerStep == 0) step(options, rows, total);
    }
    if (options.progress) options.progress(rows, total);
  }

 private:
  BagError error(std::uint64_t row, std::string message) const {
    return BagError(name_, row, "", std::move(message));
  }
  BagError sqliteError(const std::string& doing) const {
    return error(0, doing + ": SQLite error: " + sqlite3_errmsg(db_.get()));
  }

  void problem(const BagError& e, const ReadOptions& options) {
    if (!options.lenient) throw e;
    if (skipped_.count++ == 0) skipped_.firstError = e.what();
  }

  void step(const ReadOptions& options, std::uint64_t rows, std::uint64_t total) {
    if (options.progress) options.progress(rows, total);
    if (options.cancel && options.cancel->load()) throw LoadCancelled(name_);
  }

  Stmt prepare(const std::string& sql) const {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), static_cast<int>(sql.size() + 1), &raw,
                           nullptr) != SQLITE_OK) {
      sqlite3_finalize(raw);
      throw sqliteError("not a rosbag2 SQLite storage ('" + sql + "' fails)");
    }
    return Stmt(raw);
  }

  // Steps `s` to its next row; false when done; throws with the SQLite error text.
  bool next(sqlite3_stmt* s, const char* doing) const {
    const int rc = sqlite3_step(s);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw sqliteError(doing);
  }

  void open() {
    // Both tables must be tables (not views): what the queries below read is then plain data.
    std::set<std::string> tables;
    {
      Stmt s = [&] {
        sqlite3_stmt* raw = nullptr;
        const char* sql =
            "SELECT name FROM sqlite_master WHERE type = 'table' AND name IN ('topics', "
            "'messages')";
        if (sqlite3_prepare_v2(db_.get(), sql, -1, &raw, nullptr) != SQLITE_OK) {
          sqlite3_finalize(raw);
          throw sqliteError("not an SQLite database");
        }
        return Stmt(raw);
      }();
      while (next(s.get(), "not an SQLite database")) tables.insert(text(s.get(), 0));
    }
    for (const char* table : {"topics", "messages"}) {
      if (tables.count(table) == 0) {
        throw error(0, std::string("no '") + table + "' table: not a rosbag2 SQLite storage");
      }
    }

    std::map<std::int64_t, std::size_t> index;
    {
      Stmt s = prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id");
      while (next(s.get(), "reading the topics table")) {
        const std::int64_t id = sqlite3_column_int64(s.get(), 0);
        const std::string format = text(s.get(), 3);
        Topic t;
        if (format == "cdr") {
          t.encoding = Encoding::Cdr;
        } else if (format == "ros1") {
          t.encoding = Encoding::Ros1;
        } else {
          others_.insert(id);  // another serialisation (e.g. json): left out
          continue;
        }
        t.name = text(s.get(), 1);
        t.type = text(s.get(), 2);
        if (!index.try_emplace(id, topics_.size()).second) continue;  // id is the primary key
        topicIds_.push_back(id);
        topics_.push_back(std::move(t));
      }
    }
    {
      Stmt s = prepare(
          "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY "
          "topic_id");
      while (next(s.get(), "counting the messages")) {
        const std::int64_t id = sqlite3_column_int64(s.get(), 0);
        const auto n = static_cast<std::uint64_t>(sqlite3_column_int64(s.get(), 1));
        const auto it = index.find(id);
        if (it != index.end()) {
          Topic& t = topics_[it->second];
          t.count = n;
          t.firstNs = sqlite3_column_int64(s.get(), 2);
          t.lastNs = sqlite3_column_int64(s.get(), 3);
        } else if (others_.count(id) == 0) {
          if (orphans_ == 0) orphanTopic_ = id;
          orphans_ += n;
        }
      }
    }
    if (orphans_ != 0) {
      Stmt s =
          prepare("SELECT MIN(id) FROM messages WHERE topic_id = " + std::to_string(orphanTopic_));
      if (next(s.get(), "finding a message without a topic")) {
        orphanRow_ = static_cast<std::uint64_t>(sqlite3_column_int64(s.get(), 0));
      }
    }
  }

  Db db_;
  std::string name_;
  std::vector<Topic> topics_;
  std::vector<std::int64_t> topicIds_;  // the topics table's id of each topic
  std::set<std::int64_t> others_;       // topics in another serialisation
  std::uint64_t orphans_ = 0;           // messages whose topic_id has no topic
  std::int64_t orphanTopic_ = 0;
  std::uint64_t orphanRow_ = 0;
  Skipped skipped_;
};

// No string or blob can be longer than the database that holds it: with SQLite's limit at the
// database's size, a corrupt record that claims more is an error (SQLITE_TOOBIG) instead of an
// allocation of what it claims.
void limitLength(sqlite3* db, std::uint64_t databaseBytes) {
  const std::uint64_t limit = std::clamp<std::uint64_t>(databaseBytes, 4096, INT_MAX);
  sqlite3_limit(db, SQLITE_LIMIT_LENGTH, static_cast<int>(limit));
}

Db openDb(const char* path, const std::string& name) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(path, &raw, SQLITE_OPEN_READONLY, nullptr);
  Db db(raw);
  if (rc != SQLITE_OK) {
    throw BagError(name, 0, "",
                   std::string("cannot open the database: ") +
                       (raw ? sqlite3_errmsg(raw) : sqlite3_errstr(rc)));
  }
  // Defensive mode: a crafted file cannot make SQLite write or corrupt anything.
  sqlite3_db_config(db.get(), SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
  sqlite3_db_config(db.get(), SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
  return db;
}

}  // namespace

std::unique_ptr<Reader> openSqlite(const std::string& path) {
  Db db = openDb(path.c_str(), path);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec) limitLength(db.get(), size);
  return std::make_unique<SqliteReader>(std::move(db), path);
}

std::unique_ptr<Reader> openSqliteBytes(std::string_view bytes, const std::string& name) {
  Db db = openDb(":memory:", name);
  // SQLite owns the copy (freed when the database closes).
  const auto size = static_cast<sqlite3_int64>(bytes.size());
  auto* copy = static_cast<unsigned char*>(sqlite3_malloc64(bytes.empty() ? 1 : bytes.size()));
  if (copy == nullptr) throw BagError(name, 0, "", "out of memory for the database's copy");
  if (!bytes.empty()) std::copy(bytes.begin(), bytes.end(), copy);
  if (sqlite3_deserialize(db.get(), "main", copy, size, size,
                          SQLITE_DESERIALIZE_READONLY | SQLITE_DESERIALIZE_FREEONCLOSE) !=
      SQLITE_OK) {
    throw BagError(name, 0, "", std::string("not an SQLite database: ") + sqlite3_errmsg(db.get()));
  }
  limitLength(db.get(), bytes.size());
  // SQLite 3.40 reading a deserialised database allocates what a corrupt cell claims for a
  // column (tens of MB from a few KB) before it finds the damage; its structural check finds it
  // first, for the price of one pass over bytes already in memory.
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db.get(), "PRAGMA quick_check(1)", -1, &raw, nullptr) != SQLITE_OK) {
    sqlite3_finalize(raw);
    throw BagError(name, 0, "", std::string("not an SQLite database: ") + sqlite3_errmsg(db.get()));
  }
  const Stmt check(raw);
  const int rc = sqlite3_step(raw);
  if (rc != SQLITE_ROW) {
    throw BagError(name, 0, "", std::string("not an SQLite database: ") + sqlite3_errmsg(db.get()));
  }
  const std::string verdict = text(raw, 0);
  if (verdict != "ok") {
    throw BagError(name, 0, "", "a damaged SQLite database (quick_check: " + verdict + ")");
  }
  return std::make_unique<SqliteReader>(std::move(db), name);
}

}  // namespace sg::bag
