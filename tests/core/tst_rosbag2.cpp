// SPDX-License-Identifier: BSD-3-Clause
// rosbag2's two storages without ROS: MCAP (zstd, lz4 and uncompressed chunks, a file without a
// summary, one without chunks) and SQLite (.db3, the classic tables and Jazzy's). The fixtures in
// tests/data/bags/ros2/ were written by real writers (make_small_bags.mjs there: @mcap/core's
// McapWriter, @foxglove/rosmsg2-serialization's CDR MessageWriter, SQLite through better-sqlite3);
// every number below comes from that script's messages or from the layout it prints. Damaged
// inputs are those files cut, with a byte flipped or a field patched here.

#include <sqlite3.h>

#include <QTemporaryDir>
#include <QtTest>
#include <atomic>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "sonargrid/io/bag/mcap.h"
#include "sonargrid/io/bag/rosbag2_sqlite.h"
#include "sonargrid/io/log_options.h"

namespace {

using sg::bag::BagError;
using sg::bag::Reader;

std::string bagPath(const std::string& name) {
  return std::string(SONARGRID_TEST_DATA) + "/bags/ros2/" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::uint64_t le64(const std::string& b, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 8; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}
std::uint32_t le32(std::string_view b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 4; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}
float leFloat(std::string_view b, std::size_t at) {
  const std::uint32_t bits = le32(b, at);
  float f = 0;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

struct Got {
  std::string topic;
  std::int64_t logTimeNs = 0;
  std::string data;
  std::uint64_t offset = 0;
};

// Every message of the wanted topics (all when `wanted` is empty), in the order read() gives.
std::vector<Got> readAll(Reader& r, std::vector<bool> wanted = {},
                         const sg::bag::ReadOptions& options = {}) {
  if (wanted.empty()) wanted.assign(r.topics().size(), true);
  std::vector<Got> out;
  r.read(wanted, options, [&](const sg::bag::Message& m) {
    out.push_back({r.topics()[m.topic].name, m.logTimeNs, std::string(m.data), m.offset});
  });
  return out;
}

std::unique_ptr<Reader> mcapBytes(const std::string& bytes, const std::string& name) {
  return sg::bag::openMcap(sg::bag::memorySource(bytes, name));
}

// The layout make_small_bags.mjs prints (record offsets and lengths in bytes), which the tests
// below quote:
//   small_zstd.mcap (6352 bytes), zstd chunks at 77 (508), 616 (653), 1300 (322), 1653 (133),
//     1817 (132), 1980 (193), 2204 (133): a chunk per message, in time order;
//   small_lz4.mcap (5010 bytes), one lz4 chunk at 130 (1295);
//   small_none.mcap (9509 bytes), uncompressed chunks at 77 (968), 1076 (2630), 3737 (477),
//     4245 (128), 4404 (124), 4559 (804), 5394 (128);
//   small_nosummary.mcap (2254 bytes), zstd chunks at 77, 585, 1238, 1560, 1693, 1825, 2018;
//   small_unchunked.mcap (8342 bytes), Message records at 917, 2822, 3930, 4005, 4084, 4159, 4914.
// The first chunk of a channel also holds its Schema (if new) and Channel records.

// The script's stamps: T0 = 1700000000 s, then milliseconds after it.
constexpr std::int64_t kT0 = 1'700'000'000'000'000'000;
constexpr std::int64_t ms(std::int64_t m) {
  return kT0 + m * 1'000'000;
}

// What the script wrote, in time order: topic and log time (= header stamp) of each message.
const std::vector<std::pair<std::string, std::int64_t>> kWritten{
    {"/sonar/front", ms(0)},   {"/odom", ms(25)},        {"/sonar/rear", ms(50)},
    {"/sonar/front", ms(100)}, {"/sonar/rear", ms(150)}, {"/odom", ms(175)},
    {"/sonar/front", ms(200)},
};

// Runs `f`, which must throw BagError; returns it.
template <class F>
BagError bagErrorOf(F&& f) {
  try {
    f();
  } catch (const BagError& e) {
    return e;
  }
  return BagError("", 0, "", "no error");
}

// A database made with SQLite here, for the cases no rosbag2 writes.
void makeDb(const QString& path, const std::vector<std::string>& statements) {
  sqlite3* db = nullptr;
  QCOMPARE(sqlite3_open(path.toStdString().c_str(), &db), SQLITE_OK);
  for (const std::string& s : statements) {
    char* error = nullptr;
    const int rc = sqlite3_exec(db, s.c_str(), nullptr, nullptr, &error);
    if (rc != SQLITE_OK) qWarning("%s: %s", s.c_str(), error);
    sqlite3_free(error);
    QCOMPARE(rc, SQLITE_OK);
  }
  sqlite3_close(db);
}

const char* const kTopicsTable =
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
    "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL)";
const char* const kMessagesTable =
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
    "timestamp INTEGER NOT NULL, data BLOB NOT NULL)";

}  // namespace

class TstRosbag2 : public QObject {
  Q_OBJECT
 private slots:
  void mcapTopicsComeFromTheSummary();
  void everyMcapLayoutListsTheSameTopics_data();
  void everyMcapLayoutListsTheSameTopics();
  void aRangeMessageKeepsItsCdrBytes();
  void anOdometryMessageHasTheLengthOfItsCdrLayout();
  void compressionsAndTheDb3HoldEqualMessages();
  void messageOffsetsAreThoseOfChunksOrRecords();
  void onlyChunksHoldingAWantedTopicAreRead();
  void aFileWithoutSummaryIsWalkedFromTheStart();
  void aTruncatedMcapStopsAtTheCutRecord();
  void aFlippedByteInAChunkIsACrcMismatch();
  void anUnknownCompressionIsNamed();
  void aChunkClaimingAHugeSizeIsRefusedBeforeDecompressing_data();
  void aChunkClaimingAHugeSizeIsRefusedBeforeDecompressing();
  void aDamagedSummaryIsReportedAndWalkedPast();
  void garbageIsNotAnMcapFile();
  void cancellingStopsAfterAChunk();
  void sqliteTopicsCountsAndTimes();
  void aJazzyDb3WithItsExtraTablesReads();
  void sqliteFromBytesEqualsFromFile();
  void sqliteFiltersTheWantedTopics();
  void garbageIsNotADatabase();
  void aDatabaseWithoutMessagesIsNotARosbag();
  void aMessageWithoutTopicIsReportedOrSkipped();
  void sqliteReportsProgressEveryThousandRowsAndCancels();
};

void TstRosbag2::mcapTopicsComeFromTheSummary() {
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_zstd.mcap")));
  const auto& t = r->topics();
  // Channels 0, 1, 2 as the script registers them.
  QCOMPARE(t.size(), std::size_t{3});
  QCOMPARE(t[0].name, std::string("/sonar/front"));
  QCOMPARE(t[0].type, std::string("sensor_msgs/msg/Range"));
  QCOMPARE(t[1].name, std::string("/odom"));
  QCOMPARE(t[1].type, std::string("nav_msgs/msg/Odometry"));
  QCOMPARE(t[2].name, std::string("/sonar/rear"));
  QCOMPARE(t[2].type, std::string("sensor_msgs/msg/Range"));
  for (const auto& topic : t) QVERIFY(topic.encoding == sg::bag::Encoding::Cdr);
  // The schema's data: the script's ros2msg text, Range's fields first, then its dependencies.
  QVERIFY(t[0].definition.starts_with("std_msgs/Header header\nuint8 ULTRASOUND=0\n"));
  QVERIFY(t[0].definition.find("\nMSG: std_msgs/Header\n") != std::string::npos);
  QVERIFY(t[1].definition.find("\nMSG: geometry_msgs/TwistWithCovariance\n") != std::string::npos);
  // Counts from Statistics: 3 front, 2 odometry, 2 rear messages.
  QCOMPARE(t[0].count, std::uint64_t{3});
  QCOMPARE(t[1].count, std::uint64_t{2});
  QCOMPARE(t[2].count, std::uint64_t{2});
  // First and last log times of each topic (the Message Index records).
  QCOMPARE(t[0].firstNs, ms(0));
  QCOMPARE(t[0].lastNs, ms(200));
  QCOMPARE(t[1].firstNs, ms(25));
  QCOMPARE(t[1].lastNs, ms(175));
  QCOMPARE(t[2].firstNs, ms(50));
  QCOMPARE(t[2].lastNs, ms(150));
}

void TstRosbag2::everyMcapLayoutListsTheSameTopics_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("zstd, a chunk per message") << "small_zstd.mcap";
  QTest::newRow("lz4, one chunk") << "small_lz4.mcap";
  QTest::newRow("uncompressed chunks") << "small_none.mcap";
  QTest::newRow("no summary") << "small_nosummary.mcap";
  QTest::newRow("no chunks") << "small_unchunked.mcap";
}

void TstRosbag2::everyMcapLayoutListsTheSameTopics() {
  QFETCH(QString, file);
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath(file.toStdString())));
  const auto& t = r->topics();
  QCOMPARE(t.size(), std::size_t{3});
  const char* names[] = {"/sonar/front", "/odom", "/sonar/rear"};
  const std::uint64_t counts[] = {3, 2, 2};
  const std::int64_t first[] = {ms(0), ms(25), ms(50)};
  const std::int64_t last[] = {ms(200), ms(175), ms(150)};
  for (std::size_t i = 0; i < 3; ++i) {
    QCOMPARE(t[i].name, std::string(names[i]));
    QCOMPARE(t[i].count, counts[i]);
    QCOMPARE(t[i].firstNs, first[i]);
    QCOMPARE(t[i].lastNs, last[i]);
    QVERIFY(!t[i].definition.empty());
  }
  QCOMPARE(r->skipped().count, std::size_t{0});
}

// sensor_msgs/msg/Range in CDR (XCDR1, little-endian; alignment counted from the byte after the
// 4-byte encapsulation header): 4 header bytes; int32 sec, uint32 nanosec (8); frame_id as uint32
// length 12 and "sonar_front\0" (16); uint8 radiation_type (1), 3 bytes of padding to align the
// float32s; field_of_view, min_range, max_range, range (16). 4 + 8 + 16 + 1 + 3 + 16 = 48 bytes.
void TstRosbag2::aRangeMessageKeepsItsCdrBytes() {
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_lz4.mcap")));
  const std::vector<Got> got = readAll(*r, {true, false, false});
  QCOMPARE(got.size(), std::size_t{3});
  const std::string& d = got[0].data;
  QCOMPARE(d.size(), std::size_t{48});
  QCOMPARE(d.substr(0, 4), std::string("\x00\x01\x00\x00", 4));  // CDR_LE, options 0
  QCOMPARE(le32(d, 4), std::uint32_t{1700000000});               // stamp.sec
  QCOMPARE(le32(d, 8), std::uint32_t{0});                        // stamp.nanosec
  QCOMPARE(le32(d, 12), std::uint32_t{12});                      // strlen + 1
  QCOMPARE(d.substr(16, 12), std::string("sonar_front\0", 12));
  QCOMPARE(d[28], '\0');  // ULTRASOUND
  QCOMPARE(leFloat(d, 32), 0.4363f);
  QCOMPARE(leFloat(d, 36), 0.1f);
  QCOMPARE(leFloat(d, 40), 5.0f);
  QCOMPARE(leFloat(d, 44), 1.25f);
  // The third front message: stamp 100 ms later twice over, range 0.75.
  QCOMPARE(le32(got[2].data, 8), std::uint32_t{200'000'000});
  QCOMPARE(leFloat(got[2].data, 44), 0.75f);
  // "sonar_rear" is one character shorter: 11 bytes of string, the uint8 at 27, no padding
  // before the floats at 28: 44 bytes.
  const std::vector<Got> rear = readAll(*r, {false, false, true});
  QCOMPARE(rear[0].data.size(), std::size_t{44});
  QCOMPARE(leFloat(rear[0].data, 40), 2.5f);
}

// nav_msgs/msg/Odometry in CDR: 4 header bytes; stamp (8); frame_id "odom" as uint32 5 and 5
// bytes (relative 8..17); child_frame_id aligned to 4 (20), uint32 10 and "base_link\0" (to 34);
// the float64s aligned to 8 (40): pose 7, covariance 36, twist 6, covariance 36 = 85 doubles =
// 680 bytes, to 720. 4 + 720 = 724 bytes.
void TstRosbag2::anOdometryMessageHasTheLengthOfItsCdrLayout() {
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_zstd.mcap")));
  const std::vector<Got> got = readAll(*r, {false, true, false});
  QCOMPARE(got.size(), std::size_t{2});
  QCOMPARE(got[0].data.size(), std::size_t{724});
  QCOMPARE(le32(got[0].data, 24), std::uint32_t{10});
  QCOMPARE(got[0].data.substr(28, 10), std::string("base_link\0", 10));
  double x = 0;  // pose.pose.position.x at relative 40
  std::memcpy(&x, got[0].data.data() + 44, sizeof x);
  QCOMPARE(x, 1.0);
}

void TstRosbag2::compressionsAndTheDb3HoldEqualMessages() {
  std::vector<std::vector<Got>> all;
  for (const char* f : {"small_zstd.mcap", "small_lz4.mcap", "small_none.mcap",
                        "small_nosummary.mcap", "small_unchunked.mcap"}) {
    const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath(f)));
    all.push_back(readAll(*r));
  }
  for (const char* f : {"small_sqlite/small_sqlite_0.db3", "small_jazzy/small_jazzy_0.db3"}) {
    const auto r = sg::bag::openSqlite(bagPath(f));
    all.push_back(readAll(*r));
  }
  const std::vector<Got>& first = all[0];
  QCOMPARE(first.size(), kWritten.size());
  for (std::size_t i = 0; i < kWritten.size(); ++i) {
    QCOMPARE(first[i].topic, kWritten[i].first);
    QCOMPARE(first[i].logTimeNs, kWritten[i].second);
  }
  for (std::size_t k = 1; k < all.size(); ++k) {
    QCOMPARE(all[k].size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
      QCOMPARE(all[k][i].topic, first[i].topic);
      QCOMPARE(all[k][i].logTimeNs, first[i].logTimeNs);
      QCOMPARE(all[k][i].data, first[i].data);
    }
  }
}

void TstRosbag2::messageOffsetsAreThoseOfChunksOrRecords() {
  // The script's layout of small_zstd.mcap: a chunk per message at these offsets.
  const auto z = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_zstd.mcap")));
  const std::uint64_t chunks[] = {77, 616, 1300, 1653, 1817, 1980, 2204};
  const std::vector<Got> got = readAll(*z);
  for (std::size_t i = 0; i < 7; ++i) QCOMPARE(got[i].offset, chunks[i]);
  // small_lz4.mcap: one chunk at 130 holds them all.
  const auto l = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_lz4.mcap")));
  for (const Got& g : readAll(*l)) QCOMPARE(g.offset, std::uint64_t{130});
  // small_unchunked.mcap: the Message records themselves.
  const auto u = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_unchunked.mcap")));
  const std::uint64_t records[] = {917, 2822, 3930, 4005, 4084, 4159, 4914};
  const std::vector<Got> bare = readAll(*u);
  for (std::size_t i = 0; i < 7; ++i) QCOMPARE(bare[i].offset, records[i]);
}

void TstRosbag2::onlyChunksHoldingAWantedTopicAreRead() {
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_zstd.mcap")));
  std::vector<std::uint64_t> done;
  sg::bag::ReadOptions o;
  o.progress = [&](std::uint64_t d, std::uint64_t total) {
    done.push_back(d);
    QCOMPARE(total, std::uint64_t{6352});  // the file's size
  };
  const std::vector<Got> got = readAll(*r, {false, true, false}, o);
  QCOMPARE(got.size(), std::size_t{2});
  // Progress comes after each chunk read: only the two odometry chunks (at 616, 653 bytes, and
  // at 1980, 193 bytes) were read, of seven.
  const std::vector<std::uint64_t> expected{616 + 653, 1980 + 193};
  QCOMPARE(done, expected);
}

void TstRosbag2::aFileWithoutSummaryIsWalkedFromTheStart() {
  const std::string bytes = slurp(bagPath("small_nosummary.mcap"));
  // The footer (29 bytes before the closing magic) says summary_start 0: no summary.
  QCOMPARE(static_cast<int>(bytes[bytes.size() - 37]), 0x02);
  QCOMPARE(le64(bytes, bytes.size() - 28), std::uint64_t{0});
  const auto r = mcapBytes(bytes, "nosummary.mcap");
  QCOMPARE(r->topics().size(), std::size_t{3});
  QCOMPARE(r->topics()[1].count, std::uint64_t{2});  // counted by decompressing the chunks
  const std::vector<Got> got = readAll(*r, {true, false, true});
  QCOMPARE(got.size(), std::size_t{5});  // 3 front + 2 rear
  QCOMPARE(got[1].topic, std::string("/sonar/rear"));
  QCOMPARE(got[1].offset, std::uint64_t{1238});  // the third chunk in the script's layout
}

void TstRosbag2::aTruncatedMcapStopsAtTheCutRecord() {
  // Cut inside the fourth chunk of small_zstd.mcap (1653, 133 bytes): no footer, so the reader
  // walks; the three chunks before it are whole.
  const std::string bytes = slurp(bagPath("small_zstd.mcap")).substr(0, 1700);
  const auto r = mcapBytes(bytes, "cut.mcap");
  QCOMPARE(r->topics().size(), std::size_t{3});
  QCOMPARE(r->topics()[0].count, std::uint64_t{1});  // only what the first pass found
  std::size_t seen = 0;
  const BagError e = bagErrorOf([&] {
    r->read({true, true, true}, {}, [&](const sg::bag::Message&) { ++seen; });
  });
  QCOMPARE(seen, std::size_t{3});
  QCOMPARE(e.file(), std::string("cut.mcap"));
  QCOMPARE(e.offset(), std::uint64_t{1653});
  // The chunk record is 133 bytes: 9 of opcode and length, 124 of content; 1700 - 1653 - 9 = 38.
  QCOMPARE(e.message(), std::string("a Chunk record (opcode 0x06) of 124 bytes runs past the end "
                                    "of the file, which has 38 bytes left after its opcode and "
                                    "length (cut short?)"));
  QVERIFY(std::string(e.what()).starts_with("cut.mcap: offset 1653"));

  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{3});
  QCOMPARE(r->skipped().count, std::size_t{1});
  QCOMPARE(r->skipped().firstError, std::string(e.what()));

  // Cut inside a record's opcode and length: at 1653 + 5.
  const auto r2 = mcapBytes(bytes.substr(0, 1658), "cut2.mcap");
  const BagError e2 = bagErrorOf([&] { readAll(*r2); });
  QCOMPARE(e2.offset(), std::uint64_t{1653});
}

void TstRosbag2::aFlippedByteInAChunkIsACrcMismatch() {
  std::string bytes = slurp(bagPath("small_none.mcap"));
  // The fifth chunk of small_none.mcap is at 4404, 124 bytes, uncompressed: its last byte is the
  // last byte of the second rear message's range (3.0f). The records still parse; the CRC tells.
  const std::size_t chunk = 4404;
  QCOMPARE(static_cast<int>(bytes[chunk]), 0x06);
  QCOMPARE(le64(bytes, chunk + 1) + 9, std::uint64_t{124});
  bytes[chunk + 124 - 1] = static_cast<char>(bytes[chunk + 124 - 1] ^ 0x01);
  // The CRC the chunk declares: after message_start_time, message_end_time, uncompressed_size.
  const std::uint32_t declared = le32(bytes, chunk + 9 + 24);
  char crc[16];
  std::snprintf(crc, sizeof crc, "0x%08x", declared);

  const auto r = mcapBytes(bytes, "flipped.mcap");
  const BagError e = bagErrorOf([&] { readAll(*r); });
  QCOMPARE(e.file(), std::string("flipped.mcap"));
  QCOMPARE(e.offset(), std::uint64_t{chunk});
  const std::string expected =
      "chunk at offset 4404: CRC " + std::string(crc) + " but its records hash to 0x";
  QVERIFY2(e.message().starts_with(expected), e.what());

  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  const std::vector<Got> got = readAll(*r, {}, lenient);
  QCOMPARE(got.size(), std::size_t{6});  // all but the second rear message
  QCOMPARE(r->skipped().count, std::size_t{1});
  QCOMPARE(got[4].topic, std::string("/odom"));
}

void TstRosbag2::anUnknownCompressionIsNamed() {
  std::string bytes = slurp(bagPath("small_zstd.mcap"));
  // The compression string of the chunk at 1653 (the second front message): its uint32 length
  // after the 28 bytes of times, size and CRC, then "zstd". Patched to "lzma".
  const std::size_t at = 1653 + 9 + 28;
  QCOMPARE(le32(bytes, at), std::uint32_t{4});
  QCOMPARE(bytes.substr(at + 4, 4), std::string("zstd"));
  bytes.replace(at + 4, 4, "lzma");
  const auto r = mcapBytes(bytes, "lzma.mcap");
  const BagError e = bagErrorOf([&] { readAll(*r); });
  QCOMPARE(e.offset(), std::uint64_t{1653});
  QCOMPARE(e.message(),
           std::string("unknown chunk compression 'lzma'; SonarGrid reads zstd, lz4 and none"));
  // Reading only the odometry does not touch that chunk.
  QCOMPARE(readAll(*r, {false, true, false}).size(), std::size_t{2});
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{6});
  QCOMPARE(r->skipped().count, std::size_t{1});
}

void TstRosbag2::aChunkClaimingAHugeSizeIsRefusedBeforeDecompressing_data() {
  QTest::addColumn<QString>("file");
  QTest::addColumn<int>("chunk");
  // Chunks from the script's layout: the second of small_zstd.mcap (the odometry schema, channel
  // and first message) and the one chunk of small_lz4.mcap.
  QTest::newRow("zstd") << "small_zstd.mcap" << 616;
  QTest::newRow("lz4") << "small_lz4.mcap" << 130;
}

void TstRosbag2::aChunkClaimingAHugeSizeIsRefusedBeforeDecompressing() {
  QFETCH(QString, file);
  QFETCH(int, chunk);
  std::string bytes = slurp(bagPath(file.toStdString()));
  // The Chunk record's content: message_start_time, message_end_time, uncompressed_size (uint64
  // each), uncompressed_crc (uint32), compression (uint32 length + text), records (uint64 length
  // + bytes).
  const auto at = static_cast<std::size_t>(chunk) + 9 + 16;
  const std::uint64_t original = le64(bytes, at);
  const std::size_t compression = at + 8 + 4;
  const std::uint32_t nameLength = le32(bytes, compression);
  const std::uint64_t compressed = le64(bytes, compression + 4 + nameLength);
  // uncompressed_size patched to 2^30 - 1, just under the codecs' limit (kMaxChunkBytes).
  const std::uint64_t huge = (std::uint64_t{1} << 30) - 1;
  for (std::size_t i = 0; i < 8; ++i) bytes[at + i] = static_cast<char>((huge >> (8 * i)) & 0xFF);
  const auto r = mcapBytes(bytes, "huge.mcap");
  const BagError e = bagErrorOf([&] { readAll(*r); });
  QCOMPARE(e.offset(), static_cast<std::uint64_t>(chunk));
  // zstd: the frame header's content size is the original one: the data are counted, not
  // decompressed into 1 GiB. lz4: no LZ4 byte expands to more than 255.
  const std::string expected =
      file.contains("zstd")
          ? "chunk: zstd data decompress to " + std::to_string(original) + " bytes, not the " +
                std::to_string(huge) + " the chunk declares"
          : "chunk: " + std::to_string(compressed) + " bytes of LZ4 data cannot hold the " +
                std::to_string(huge) + " bytes the chunk declares";
  QCOMPARE(e.message(), expected);
}

void TstRosbag2::aDamagedSummaryIsReportedAndWalkedPast() {
  std::string bytes = slurp(bagPath("small_zstd.mcap"));
  // summary_start is the footer's first field; flip a byte 20 bytes into the summary.
  const std::uint64_t summary = le64(bytes, bytes.size() - 8 - 20);
  QVERIFY(summary > 2204 && summary < bytes.size());
  bytes[summary + 20] = static_cast<char>(bytes[summary + 20] ^ 0x20);
  const auto r = mcapBytes(bytes, "summary.mcap");
  QCOMPARE(r->topics().size(), std::size_t{3});  // from the walk instead
  const BagError e = bagErrorOf([&] { readAll(*r); });
  QCOMPARE(e.offset(), summary);
  QVERIFY2(e.message().starts_with("summary section: CRC 0x"), e.what());
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{7});
  QCOMPARE(r->skipped().count, std::size_t{1});
}

void TstRosbag2::garbageIsNotAnMcapFile() {
  const BagError e = bagErrorOf([] { mcapBytes("SQLite format 3\0 and so on", "junk.mcap"); });
  QCOMPARE(e.file(), std::string("junk.mcap"));
  QCOMPARE(e.offset(), std::uint64_t{0});
  QVERIFY2(e.message().starts_with("not an MCAP file"), e.what());
  // The magic, then something that is not the Header record (opcode 0x01).
  const BagError h = bagErrorOf(
      [] { mcapBytes(std::string("\x89MCAP0\r\n\x05", 9) + std::string(20, '\0'), "h"); });
  QCOMPARE(h.offset(), std::uint64_t{8});
  QVERIFY2(h.message().find("found opcode 0x05") != std::string::npos, h.what());
}

void TstRosbag2::cancellingStopsAfterAChunk() {
  const auto r = sg::bag::openMcap(sg::bag::fileSource(bagPath("small_zstd.mcap")));
  std::atomic<bool> cancel{true};
  sg::bag::ReadOptions o;
  o.cancel = &cancel;
  std::size_t seen = 0;
  QVERIFY_THROWS_EXCEPTION(sg::LoadCancelled,
                           r->read({true, true, true}, o, [&](auto&) { ++seen; }));
  QCOMPARE(seen, std::size_t{1});  // the first chunk's message, then the check
}

void TstRosbag2::sqliteTopicsCountsAndTimes() {
  const auto r = sg::bag::openSqlite(bagPath("small_sqlite/small_sqlite_0.db3"));
  const auto& t = r->topics();
  // The topics table's rows, ids 1..3 in the script's order.
  QCOMPARE(t.size(), std::size_t{3});
  QCOMPARE(t[0].name, std::string("/sonar/front"));
  QCOMPARE(t[1].type, std::string("nav_msgs/msg/Odometry"));
  QCOMPARE(t[2].name, std::string("/sonar/rear"));
  QVERIFY(t[2].encoding == sg::bag::Encoding::Cdr);
  QVERIFY(t[0].definition.empty());  // the classic tables carry no definitions
  QCOMPARE(t[0].count, std::uint64_t{3});
  QCOMPARE(t[1].count, std::uint64_t{2});
  QCOMPARE(t[1].firstNs, ms(25));
  QCOMPARE(t[1].lastNs, ms(175));
  // Message::offset is the row id: inserted in time order, 1..7.
  const std::vector<Got> got = readAll(*r);
  for (std::size_t i = 0; i < got.size(); ++i) QCOMPARE(got[i].offset, std::uint64_t{i + 1});
}

void TstRosbag2::aJazzyDb3WithItsExtraTablesReads() {
  // schema, metadata and message_definitions tables, topics.type_description_hash.
  const auto r = sg::bag::openSqlite(bagPath("small_jazzy/small_jazzy_0.db3"));
  QCOMPARE(r->topics().size(), std::size_t{3});
  QCOMPARE(r->topics()[2].count, std::uint64_t{2});
  QCOMPARE(r->topics()[2].firstNs, ms(50));
  QCOMPARE(readAll(*r).size(), std::size_t{7});
}

void TstRosbag2::sqliteFromBytesEqualsFromFile() {
  const std::string path = bagPath("small_sqlite/small_sqlite_0.db3");
  const auto f = sg::bag::openSqlite(path);
  const auto b = sg::bag::openSqliteBytes(slurp(path), "mem.db3");
  const std::vector<Got> x = readAll(*f), y = readAll(*b);
  QCOMPARE(y.size(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    QCOMPARE(y[i].data, x[i].data);
    QCOMPARE(y[i].offset, x[i].offset);
  }
}

void TstRosbag2::sqliteFiltersTheWantedTopics() {
  const auto r = sg::bag::openSqlite(bagPath("small_sqlite/small_sqlite_0.db3"));
  std::vector<std::uint64_t> done;
  sg::bag::ReadOptions o;
  o.progress = [&](std::uint64_t d, std::uint64_t total) {
    done.push_back(d);
    QCOMPARE(total, std::uint64_t{2});  // the rear sonar's rows
  };
  const std::vector<Got> got = readAll(*r, {false, false, true}, o);
  QCOMPARE(got.size(), std::size_t{2});
  QCOMPARE(got[0].offset, std::uint64_t{3});  // rows 3 and 5 in the script's order
  QCOMPARE(got[1].offset, std::uint64_t{5});
  QCOMPARE(got[1].logTimeNs, ms(150));
  QCOMPARE(done, std::vector<std::uint64_t>{2});  // under 1000 rows: once, at the end
}

void TstRosbag2::garbageIsNotADatabase() {
  const std::string junk(4096, 'x');
  const BagError e = bagErrorOf([&] { sg::bag::openSqliteBytes(junk, "junk.db3"); });
  QCOMPARE(e.file(), std::string("junk.db3"));
  QCOMPARE(e.offset(), std::uint64_t{0});
  QVERIFY2(e.message().find("file is not a database") != std::string::npos, e.what());
  const BagError missing = bagErrorOf([] { sg::bag::openSqlite("/nonexistent/x.db3"); });
  QCOMPARE(missing.file(), std::string("/nonexistent/x.db3"));
  QVERIFY2(missing.message().find("unable to open") != std::string::npos, missing.what());
}

void TstRosbag2::aDatabaseWithoutMessagesIsNotARosbag() {
  QTemporaryDir dir;
  const QString path = dir.filePath("topics_only.db3");
  makeDb(path, {kTopicsTable});
  const BagError e = bagErrorOf([&] { sg::bag::openSqlite(path.toStdString()); });
  QCOMPARE(e.message(), std::string("no 'messages' table: not a rosbag2 SQLite storage"));
}

void TstRosbag2::aMessageWithoutTopicIsReportedOrSkipped() {
  QTemporaryDir dir;
  const QString path = dir.filePath("orphan.db3");
  makeDb(path, {kTopicsTable, kMessagesTable,
                "INSERT INTO topics VALUES (1, '/sonar', 'sensor_msgs/msg/Range', 'cdr', '')",
                "INSERT INTO messages VALUES (1, 1, 10, x'00010000')",
                "INSERT INTO messages VALUES (2, 7, 20, x'00010000')",
                "INSERT INTO messages VALUES (3, 7, 30, x'00010000')",
                "INSERT INTO messages VALUES (4, 1, 40, x'00010000')"});
  const auto r = sg::bag::openSqlite(path.toStdString());
  QCOMPARE(r->topics()[0].count, std::uint64_t{2});
  const BagError e = bagErrorOf([&] { readAll(*r); });
  QCOMPARE(e.offset(), std::uint64_t{2});  // the row id of the first message of topic_id 7
  QVERIFY2(e.message().starts_with("message id 2: topic_id 7 is not in the topics table"),
           e.what());
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{2});
  QCOMPARE(r->skipped().count, std::size_t{2});  // rows 2 and 3
}

void TstRosbag2::sqliteReportsProgressEveryThousandRowsAndCancels() {
  QTemporaryDir dir;
  const QString path = dir.filePath("rows.db3");
  makeDb(path, {kTopicsTable, kMessagesTable,
                "INSERT INTO topics VALUES (1, '/sonar', 'sensor_msgs/msg/Range', 'cdr', '')",
                "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 2500) "
                "INSERT INTO messages SELECT i, 1, i, x'00' FROM n"});
  const auto r = sg::bag::openSqlite(path.toStdString());
  std::vector<std::uint64_t> done;
  sg::bag::ReadOptions o;
  o.progress = [&](std::uint64_t d, std::uint64_t total) {
    done.push_back(d);
    QCOMPARE(total, std::uint64_t{2500});
  };
  QCOMPARE(readAll(*r, {}, o).size(), std::size_t{2500});
  QCOMPARE(done, (std::vector<std::uint64_t>{1000, 2000, 2500}));

  std::atomic<bool> cancel{true};
  o.progress = nullptr;
  o.cancel = &cancel;
  std::size_t seen = 0;
  QVERIFY_THROWS_EXCEPTION(sg::LoadCancelled,
                           r->read({true}, o, [&](const sg::bag::Message&) { ++seen; }));
  QCOMPARE(seen, std::size_t{1000});
}

QTEST_APPLESS_MAIN(TstRosbag2)
#include "tst_rosbag2.moc"
