// SPDX-License-Identifier: BSD-3-Clause
// ROS 1 bags (format 2.0) written by Debian's python3-rosbag (tests/data/bags/ros1/
// make_small_bags.py): topics from the index, messages with their times and bytes, the three
// chunk compressions, wanted-topic filtering, a bag without index, a bag without chunks, progress
// and cancel, and bad input patched from the good fixtures (BagError naming the file and offset;
// lenient reads skip and count).

#include <QTemporaryDir>
#include <QtTest>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "sonargrid/io/bag/bag.h"
#include "sonargrid/io/bag/rosbag1.h"
#include "sonargrid/io/log_options.h"

namespace {

using sg::bag::BagError;

const std::string kDir = SONARGRID_TEST_DATA "/bags/ros1/";

// The script's times: T0 = 1700000000 s; /sonar at T0 + 0, .1, .2, .3 s, /odom at T0 + .05, .15,
// .25 s, written in time order.
constexpr std::int64_t kT0 = 1700000000LL * 1000000000LL;
constexpr std::int64_t kMs = 1000000;

// Where the first chunk starts in every fixture: the 13-byte version line "#ROSBAG V2.0\n", then
// the bag header record, which the writer pads to 4096 bytes of header and data, plus its two
// 4-byte lengths: 13 + 4 + 4096 + 4 = 4117.
constexpr std::uint64_t kFirstChunk = 4117;

// small_chunks.bag's chunks (one message each), as rosbag's Bag._chunk_headers lists them; the
// second holds /odom only.
const std::vector<std::uint64_t> kChunks = {4117, 6027, 7794, 8009, 8259, 8474, 8723};

// Message sizes from the ROS 1 layout (little-endian, packed, strings as uint32 length + bytes):
// sensor_msgs/Range = Header (uint32 seq, time stamp 8, string frame_id "sonar0" 4 + 6) + uint8
// radiation_type + 4 float32 = 4 + 8 + 10 + 1 + 16 = 39 bytes.
// nav_msgs/Odometry = Header (4 + 8 + 4 + "odom" 4) + child_frame_id ("base_link" 4 + 9) + pose
// (7 float64 = 56) + covariance (36 float64 = 288) + twist (6 float64 = 48) + covariance (288)
// = 20 + 13 + 56 + 288 + 48 + 288 = 713 bytes.
constexpr std::size_t kRangeBytes = 39;
constexpr std::size_t kOdometryBytes = 713;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // the test hosts are little-endian, like the format
  return v;
}

void put32(std::string& b, std::size_t at, std::uint32_t v) {
  std::memcpy(b.data() + at, &v, 4);
}
void put64(std::string& b, std::size_t at, std::uint64_t v) {
  std::memcpy(b.data() + at, &v, 8);
}

// Where the value of the header field `name=` first appears at or after `from`.
std::size_t valueOf(const std::string& b, const std::string& name, std::size_t from = 0) {
  const std::size_t at = b.find(name + "=", from);
  if (at == std::string::npos) return at;
  return at + name.size() + 1;
}

// The first byte of a chunk record's data: after its header length, header and data length.
std::size_t chunkData(const std::string& b, std::size_t chunkPos) {
  return chunkPos + 4 + le32(b, chunkPos) + 4;
}

// A message record's op field as the writer puts it first in the header: "op=" + 0x02 with its
// 4-byte length 4.
const std::string kMessageOp("\x04\x00\x00\x00op=\x02", 8);

struct Got {
  std::size_t topic;
  std::int64_t timeNs;
  std::string data;
  std::uint64_t offset;
  bool operator==(const Got&) const = default;
};

std::unique_ptr<sg::bag::Reader> open(const std::string& bytes, const std::string& name) {
  return sg::bag::openRos1(sg::bag::memorySource(bytes, name));
}

std::vector<Got> readAll(sg::bag::Reader& r, std::vector<bool> wanted = {},
                         const sg::bag::ReadOptions& options = {}) {
  if (wanted.empty()) wanted.assign(r.topics().size(), true);
  std::vector<Got> out;
  r.read(wanted, options, [&](const sg::bag::Message& m) {
    out.push_back({m.topic, m.logTimeNs, std::string(m.data), m.offset});
  });
  return out;
}

// what() of the BagError a strict read of every topic throws, or what happened instead.
QString strictError(sg::bag::Reader& r) {
  try {
    readAll(r);
  } catch (const BagError& e) {
    return QString::fromStdString(e.what());
  } catch (const std::exception& e) {
    return "unexpected exception: " + QString::fromStdString(e.what());
  }
  return "no error";
}

QString openError(const std::string& bytes, const std::string& name) {
  try {
    open(bytes, name);
  } catch (const BagError& e) {
    return QString::fromStdString(e.what());
  }
  return "no error";
}

// The 7 messages without their offsets (which differ between the fixtures).
std::vector<Got> withoutOffsets(std::vector<Got> v) {
  for (Got& g : v) g.offset = 0;
  return v;
}

float floatAt(const std::string& b, std::size_t at) {
  float f = 0;
  std::memcpy(&f, b.data() + at, 4);
  return f;
}

}  // namespace

class TstRosbag1 : public QObject {
  Q_OBJECT
 private slots:
  void containersAreToldApartByTheirFirstBytes();
  void topicsComeFromTheIndex();
  void messagesComeInStoredOrderWithTheirTimesAndBytes();
  void everyCompressionGivesTheSameMessages();
  void wantedTopicsFilterTheMessages();
  void onlyChunksHoldingAWantedTopicAreRead();
  void anUncompressedChunkGivesOnlyItsWantedRecords();
  void aBagWithoutIndexIsWalkedFromTheStart();
  void anIndexPastTheEndOrNotThereIsWalkedToo();
  void messagesOutsideChunksAreRead();
  void progressComesAfterEachChunkAndCancelStops();
  void aFileThatDoesNotOpenNamesItsPath();
  void readingPastTheEndSaysTheFileIsCutShort();
  void aTruncatedFileNamesTheRecordItCuts();
  void aRecordingCutShortKeepsItsCompleteChunks();
  void aCorruptedChunkSizeIsAnError();
  void anUnknownCompressionIsNamed();
  void badRecordsInsideAChunkNameTheChunkAndRecord();
  void aBadVersionLineOrBagHeaderStopsTheOpen();
};

void TstRosbag1::containersAreToldApartByTheirFirstBytes() {
  using sg::bag::Container;
  QCOMPARE(sg::bag::detectContainer(readBytes(kDir + "small_none.bag").substr(0, 64)),
           Container::Ros1);
  QCOMPARE(sg::bag::detectContainer(std::string_view("\x89MCAP0\r\n\x01", 9)), Container::Mcap);
  QCOMPARE(sg::bag::detectContainer(std::string_view("SQLite format 3\0\x10", 17)),
           Container::Sqlite);
  QCOMPARE(sg::bag::detectContainer("#ROSBAG V1.2\n"), Container::Unknown);
  QCOMPARE(sg::bag::detectContainer("SQLite format 3"), Container::Unknown);  // no NUL
  QCOMPARE(sg::bag::detectContainer(""), Container::Unknown);
}

void TstRosbag1::topicsComeFromTheIndex() {
  const auto r = sg::bag::openRos1(sg::bag::fileSource(kDir + "small_none.bag"));
  const std::vector<sg::bag::Topic>& t = r->topics();
  QCOMPARE(t.size(), std::size_t{2});
  // Connection 0 is the first topic the script writes (/sonar), connection 1 /odom.
  QCOMPARE(t[0].name, std::string("/sonar"));
  QCOMPARE(t[0].type, std::string("sensor_msgs/Range"));
  QCOMPARE(t[0].encoding, sg::bag::Encoding::Ros1);
  QCOMPARE(t[0].count, std::uint64_t{4});  // the script's 4 Range messages
  QCOMPARE(t[0].firstNs, kT0);
  QCOMPARE(t[0].lastNs, kT0 + 300 * kMs);
  // The definition genpy writes into the connection header (Range._full_text).
  QVERIFY(t[0].definition.starts_with("# Single range reading from an active ranger"));
  QVERIFY(t[0].definition.find("float32 range") != std::string::npos);
  QCOMPARE(t[1].name, std::string("/odom"));
  QCOMPARE(t[1].type, std::string("nav_msgs/Odometry"));
  QCOMPARE(t[1].count, std::uint64_t{3});  // the script's 3 Odometry messages
  QCOMPARE(t[1].firstNs, kT0 + 50 * kMs);  // exact, not the chunk's start time (T0)
  QCOMPARE(t[1].lastNs, kT0 + 250 * kMs);  // nor its end time (T0 + .3 s)
  QVERIFY(t[1].definition.find("geometry_msgs/PoseWithCovariance pose") != std::string::npos);

  // With a chunk per message, each time comes from its own chunk's index data.
  const auto c = sg::bag::openRos1(sg::bag::fileSource(kDir + "small_chunks.bag"));
  QCOMPARE(c->topics()[1].firstNs, kT0 + 50 * kMs);
  QCOMPARE(c->topics()[1].lastNs, kT0 + 250 * kMs);
  QCOMPARE(c->topics()[0].count, std::uint64_t{4});
}

void TstRosbag1::messagesComeInStoredOrderWithTheirTimesAndBytes() {
  const auto r = sg::bag::openRos1(sg::bag::fileSource(kDir + "small_none.bag"));
  const std::vector<Got> got = readAll(*r);
  QCOMPARE(got.size(), std::size_t{7});
  for (std::size_t i = 0; i < got.size(); ++i) {
    const Got& g = got[i];
    QCOMPARE(g.offset, kFirstChunk);  // all in the one chunk
    const std::uint32_t k = static_cast<std::uint32_t>(i / 2);
    if (i % 2 == 0) {  // /sonar, Range k
      QCOMPARE(g.topic, std::size_t{0});
      QCOMPARE(g.timeNs, kT0 + k * 100 * kMs);
      QCOMPARE(g.data.size(), kRangeBytes);
      // Header: seq (the script sets k), stamp (1700000000 s = 0x6553f100, k * 0.1 s), frame_id.
      QCOMPARE(le32(g.data, 0), k);
      QCOMPARE(le32(g.data, 4), 1700000000u);
      QCOMPARE(le32(g.data, 8), k * 100000000u);
      QCOMPARE(g.data.substr(12, 10), std::string("\x06\x00\x00\x00sonar0", 10));
      QCOMPARE(g.data[22], '\0');                      // radiation_type ULTRASOUND
      QCOMPARE(floatAt(g.data, 35), 1.0f + float(k));  // range, the last float32
    } else {                                           // /odom, Odometry k
      QCOMPARE(g.topic, std::size_t{1});
      QCOMPARE(g.timeNs, kT0 + k * 100 * kMs + 50 * kMs);
      QCOMPARE(g.data.size(), kOdometryBytes);
      QCOMPARE(le32(g.data, 0), 10 + k);  // seq 10, 11, 12
      QCOMPARE(g.data.substr(12, 8), std::string("\x04\x00\x00\x00odom", 8));
      QCOMPARE(g.data.substr(20, 13), std::string("\x09\x00\x00\x00"
                                                  "base_link",
                                                  13));
    }
  }
}

void TstRosbag1::everyCompressionGivesTheSameMessages() {
  const std::vector<Got> none =
      readAll(*sg::bag::openRos1(sg::bag::fileSource(kDir + "small_none.bag")));
  for (const char* name :
       {"small_bz2.bag", "small_lz4.bag", "small_chunks.bag", "small_noindex.bag"}) {
    const auto r = sg::bag::openRos1(sg::bag::fileSource(kDir + name));
    QCOMPARE(r->topics().size(), std::size_t{2});
    QVERIFY2(withoutOffsets(readAll(*r)) == withoutOffsets(none), name);
    QCOMPARE(r->skipped().count, std::size_t{0});
  }
  // A chunk per message: each message's offset is its chunk's.
  const std::vector<Got> chunks =
      readAll(*sg::bag::openRos1(sg::bag::fileSource(kDir + "small_chunks.bag")));
  for (std::size_t i = 0; i < chunks.size(); ++i) QCOMPARE(chunks[i].offset, kChunks[i]);
}

void TstRosbag1::wantedTopicsFilterTheMessages() {
  for (const char* name : {"small_lz4.bag", "small_chunks.bag", "small_noindex.bag"}) {
    const auto r = sg::bag::openRos1(sg::bag::fileSource(kDir + name));
    const std::vector<Got> odom = readAll(*r, {false, true});
    QCOMPARE(odom.size(), std::size_t{3});  // the 3 Odometry messages
    for (std::size_t i = 0; i < odom.size(); ++i) {
      QCOMPARE(odom[i].topic, std::size_t{1});
      QCOMPARE(odom[i].timeNs, kT0 + std::int64_t(i) * 100 * kMs + 50 * kMs);
    }
    QCOMPARE(readAll(*r, {true, false}).size(), std::size_t{4});  // the 4 Range messages
    // A shorter wanted vector leaves the topics past its end out.
    QCOMPARE(readAll(*r, {true}).size(), std::size_t{4});
    QCOMPARE(readAll(*r, {false, false}).size(), std::size_t{0});
  }
}

void TstRosbag1::onlyChunksHoldingAWantedTopicAreRead() {
  // Break the second chunk of small_chunks.bag (its one /odom message): declare one more
  // uncompressed byte than its LZ4 frame gives.
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  {
    std::string b = readBytes(kDir + "small_chunks.bag");
    const std::size_t size = valueOf(b, "size", kChunks[1]);
    QVERIFY(size < kChunks[2]);
    put32(b, size, le32(b, size) + 1);
    const auto r = open(b, "broken.bag");
    // The index says which chunks hold /sonar: the broken one is never decompressed.
    QCOMPARE(readAll(*r, {true, false}).size(), std::size_t{4});
    const QString e = strictError(*r);
    QVERIFY2(e.startsWith("broken.bag: offset 6027: the lz4 chunk does not decompress to "),
             qPrintable(e));
    // Lenient: every other message, and the chunk counted.
    QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{6});
    QCOMPARE(r->skipped().count, std::size_t{1});
    QCOMPARE(QString::fromStdString(r->skipped().firstError), e);
    // skipped() is the last read's: a clean read leaves it empty.
    readAll(*r, {true, false}, lenient);
    QCOMPARE(r->skipped().count, std::size_t{0});
  }
  {
    // Without index the same chunk is where /odom's connection record is: /odom is lost, and the
    // broken chunk may hold any topic, so a strict read of /sonar stops there too.
    std::string b = readBytes(kDir + "small_noindex.bag");
    const std::size_t size = valueOf(b, "size", kChunks[1]);
    put32(b, size, le32(b, size) + 1);
    const auto r = open(b, "noindex.bag");
    QCOMPARE(r->topics().size(), std::size_t{1});
    QCOMPARE(r->topics()[0].name, std::string("/sonar"));
    QCOMPARE(r->topics()[0].count, std::uint64_t{4});
    QVERIFY(strictError(*r).startsWith("noindex.bag: offset 6027: the lz4 chunk does not "));
    QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{4});
    // The broken chunk, then /odom's two other chunks: messages on an undeclared connection.
    QCOMPARE(r->skipped().count, std::size_t{3});
  }
}

// small_none.bag's one uncompressed chunk holds both topics: a read of one of them takes its
// records at the offsets of the index data records after the chunk, and gives what a read of the
// whole chunk gives for that topic (bytes, times, order, the chunk's offset).
void TstRosbag1::anUncompressedChunkGivesOnlyItsWantedRecords() {
  const std::string path = kDir + "small_none.bag";
  const auto r = sg::bag::openRos1(sg::bag::fileSource(path));
  const std::vector<Got> all = readAll(*r);
  QCOMPARE(all.size(), std::size_t{7});
  for (const std::size_t topic : {std::size_t{0}, std::size_t{1}}) {
    std::vector<bool> wanted(2, false);
    wanted[topic] = true;
    std::vector<Got> expected;
    for (const Got& g : all)
      if (g.topic == topic) expected.push_back(g);
    QVERIFY(readAll(*r, wanted) == expected);
  }
  // /odom's first message is at T0 + 0.05 s (sec 1700000000, nsec 50 000 000, little-endian): its
  // index entry is the first such 8 bytes after the chunk, and the entry's 4-byte offset into the
  // chunk follows them. Offset 0 is the chunk's first record, a connection record.
  std::string b = readBytes(path);
  const std::size_t chunkEnd = chunkData(b, kFirstChunk) + le32(b, valueOf(b, "size", kFirstChunk));
  std::string stamp(8, '\0');
  put32(stamp, 0, 1700000000u);
  put32(stamp, 4, 50000000u);
  const std::size_t entry = b.find(stamp, chunkEnd);
  QVERIFY(entry != std::string::npos);
  QVERIFY(le32(b, entry + 8) > 0);
  put32(b, entry + 8, 0);
  const auto broken = open(b, "broken.bag");
  try {
    readAll(*broken, {false, true});
    QFAIL("a message the index misplaces was read");
  } catch (const BagError& e) {
    QCOMPARE(QString(e.what()),
             QStringLiteral("broken.bag: offset 4117 (topic /odom): chunk at offset 4117, record "
                            "at byte 0 of the chunk: the index puts a message of /odom here, but "
                            "the record is not one"));
  }
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  const std::vector<Got> odom = readAll(*broken, {false, true}, lenient);
  QCOMPARE(odom.size(), std::size_t{2});  // the other two /odom messages
  QCOMPARE(broken->skipped().count, std::size_t{1});
  // The /sonar records' index is intact.
  QCOMPARE(readAll(*broken, {true, false}).size(), std::size_t{4});
}

void TstRosbag1::aBagWithoutIndexIsWalkedFromTheStart() {
  // small_noindex.bag: small_chunks.bag cut at its index_pos, index_pos 0 (the script).
  const auto r = sg::bag::openRos1(sg::bag::fileSource(kDir + "small_noindex.bag"));
  const auto& t = r->topics();
  QCOMPARE(t.size(), std::size_t{2});
  QCOMPARE(t[0].name, std::string("/sonar"));  // declared in the first chunk
  QCOMPARE(t[0].type, std::string("sensor_msgs/Range"));
  QCOMPARE(t[0].count, std::uint64_t{4});  // counted on the constructor's walk
  QCOMPARE(t[0].firstNs, kT0);
  QCOMPARE(t[0].lastNs, kT0 + 300 * kMs);
  QCOMPARE(t[1].name, std::string("/odom"));
  QCOMPARE(t[1].type, std::string("nav_msgs/Odometry"));
  QCOMPARE(t[1].count, std::uint64_t{3});
  QCOMPARE(t[1].firstNs, kT0 + 50 * kMs);
  QCOMPARE(t[1].lastNs, kT0 + 250 * kMs);
  QVERIFY(t[1].definition.find("geometry_msgs/PoseWithCovariance pose") != std::string::npos);
  const std::vector<Got> got = readAll(*r);
  QCOMPARE(got.size(), std::size_t{7});
  for (std::size_t i = 0; i < got.size(); ++i) QCOMPARE(got[i].offset, kChunks[i]);

  // The walk takes a chunk's connections from the index data records after it: break the third
  // chunk (the second Range message, on a connection the first chunk declared) and the walk
  // still counts its message, and a read of /odom does not decompress it.
  std::string b = readBytes(kDir + "small_noindex.bag");
  const std::size_t size = valueOf(b, "size", kChunks[2]);
  put32(b, size, le32(b, size) + 1);
  const auto broken = open(b, "third.bag");
  QCOMPARE(broken->topics()[0].count, std::uint64_t{4});
  QCOMPARE(readAll(*broken, {false, true}).size(), std::size_t{3});
  QVERIFY(strictError(*broken).startsWith("third.bag: offset 7794: the lz4 chunk does not "));
}

void TstRosbag1::anIndexPastTheEndOrNotThereIsWalkedToo() {
  const std::string good = readBytes(kDir + "small_lz4.bag");
  const std::vector<Got> expected = readAll(*open(good, "good.bag"));
  const std::size_t at = valueOf(good, "index_pos");
  // Past the end (a copy cut short after the writer finished), and pointing at the chunk
  // instead of connection and chunk info records.
  for (const std::uint64_t indexPos : {std::uint64_t{1} << 40, std::uint64_t{kFirstChunk}}) {
    std::string b = good;
    put64(b, at, indexPos);
    const auto r = open(b, "moved.bag");
    QCOMPARE(r->topics().size(), std::size_t{2});
    QCOMPARE(r->topics()[0].count, std::uint64_t{4});
    QCOMPARE(r->topics()[1].count, std::uint64_t{3});
    QVERIFY(readAll(*r) == expected);
  }
}

void TstRosbag1::messagesOutsideChunksAreRead() {
  // A bag without chunks, built from small_none.bag: its version line and bag header (index_pos
  // 0), then the records of its one uncompressed chunk at the top level.
  const std::string none = readBytes(kDir + "small_none.bag");
  std::string b = none.substr(0, kFirstChunk);
  put64(b, valueOf(b, "index_pos"), 0);
  const std::size_t data = chunkData(none, kFirstChunk);
  b += none.substr(data, le32(none, valueOf(none, "size", kFirstChunk)));
  const auto r = open(b, "flat.bag");
  QCOMPARE(r->topics().size(), std::size_t{2});
  QCOMPARE(r->topics()[0].count, std::uint64_t{4});
  const std::vector<Got> got = readAll(*r);
  const std::vector<Got> expected =
      readAll(*sg::bag::openRos1(sg::bag::fileSource(kDir + "small_none.bag")));
  QVERIFY(withoutOffsets(got) == withoutOffsets(expected));
  // Each message's offset is its own record's: 4 bytes before its header's first field (op).
  std::size_t from = kFirstChunk;
  for (const Got& g : got) {
    const std::size_t op = b.find(kMessageOp, from);
    QCOMPARE(g.offset, std::uint64_t{op - 4});
    from = op + 1;
  }

  // The same records after the header of a chunk the writer had not finished (both sizes still
  // 0, as the writers put them before the chunk's records): an empty chunk, then the records.
  std::string chunkHeader = none.substr(kFirstChunk, data - kFirstChunk);
  put32(chunkHeader, valueOf(chunkHeader, "size"), 0);
  put32(chunkHeader, chunkHeader.size() - 4, 0);  // data_len
  std::string unfinished = b.substr(0, kFirstChunk) + chunkHeader + b.substr(kFirstChunk);
  const auto u = open(unfinished, "unfinished.bag");
  QVERIFY(withoutOffsets(readAll(*u)) == withoutOffsets(expected));
  QCOMPARE(u->topics()[1].count, std::uint64_t{3});
}

void TstRosbag1::progressComesAfterEachChunkAndCancelStops() {
  const std::string path = kDir + "small_chunks.bag";
  const auto r = sg::bag::openRos1(sg::bag::fileSource(path));
  std::vector<std::pair<std::uint64_t, std::uint64_t>> calls;
  sg::bag::ReadOptions o;
  o.progress = [&](std::uint64_t done, std::uint64_t total) { calls.emplace_back(done, total); };
  readAll(*r, {}, o);
  QCOMPARE(calls.size(), kChunks.size());  // once per chunk
  const std::uint64_t size = readBytes(path).size();
  for (std::size_t i = 0; i < calls.size(); ++i) {
    QCOMPARE(calls[i].second, size);
    // Done up to the next chunk, the last up to the end of the file.
    QCOMPARE(calls[i].first, i + 1 < kChunks.size() ? kChunks[i + 1] : size);
  }
  // A cancel set during the first chunk stops the read after it.
  std::atomic<bool> cancel{false};
  o.progress = nullptr;
  o.cancel = &cancel;
  std::size_t seen = 0;
  QVERIFY_THROWS_EXCEPTION(sg::LoadCancelled, r->read({true, true}, o, [&](const auto&) {
    ++seen;
    cancel = true;
  }));
  QCOMPARE(seen, std::size_t{1});
  // The walk without index checks it after each chunk as well.
  const auto n = sg::bag::openRos1(sg::bag::fileSource(kDir + "small_noindex.bag"));
  cancel = false;
  seen = 0;
  QVERIFY_THROWS_EXCEPTION(sg::LoadCancelled, n->read({true, true}, o, [&](const auto&) {
    ++seen;
    cancel = true;
  }));
  QCOMPARE(seen, std::size_t{1});
}

void TstRosbag1::aFileThatDoesNotOpenNamesItsPath() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string missing = dir.filePath("missing.bag").toStdString();
  try {
    sg::bag::fileSource(missing);
    QFAIL("a missing file opened");
  } catch (const BagError& e) {
    QCOMPARE(e.file(), missing);
    QCOMPARE(e.offset(), std::uint64_t{0});
    QVERIFY(QByteArray(e.what()).startsWith((missing + ": offset 0: cannot open").c_str()));
  }
  QVERIFY_THROWS_EXCEPTION(BagError, sg::bag::fileSource(dir.path().toStdString()));
}

void TstRosbag1::readingPastTheEndSaysTheFileIsCutShort() {
  const std::string path = kDir + "small_none.bag";
  const auto file = sg::bag::fileSource(path);
  const auto memory = sg::bag::memorySource(readBytes(path), "mem.bag");
  QCOMPARE(file->size(), std::uint64_t{19627});  // the fixture's size
  QCOMPARE(memory->size(), file->size());
  std::string a, b;
  file->read(4117, 100, a);
  memory->read(4117, 100, b);
  QCOMPARE(a, b);
  QCOMPARE(a.size(), std::size_t{100});
  for (const sg::bag::ByteSource* s : {file.get(), memory.get()}) {
    try {
      s->read(19600, 50, a);
      QFAIL("read past the end");
    } catch (const BagError& e) {
      // 19600 + 50 = 19650, 23 bytes past the end at 19627.
      QCOMPARE(QString(e.what()),
               QString::fromStdString(s->name()) +
                   ": offset 19600: the file is cut short: file ends at byte 19627, 23 bytes "
                   "short of the record");
    }
  }
}

void TstRosbag1::aTruncatedFileNamesTheRecordItCuts() {
  const std::string none = readBytes(kDir + "small_none.bag");
  // Cut inside the one chunk: the index is gone with it, the walk finds no complete chunk.
  const auto r = open(none.substr(0, 10000), "cut.bag");
  QCOMPARE(r->topics().size(), std::size_t{0});
  const QString e = strictError(*r);
  QVERIFY2(e.startsWith("cut.bag: offset 4117: the file is cut short: file ends at byte 10000"),
           qPrintable(e));
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{0});
  QCOMPARE(r->skipped().count, std::size_t{1});
  // Cut inside the bag header: the file as a whole is bad.
  const QString h = openError(none.substr(0, 100), "head.bag");
  QVERIFY2(h.startsWith("head.bag: offset 13: the file is cut short: file ends at byte 100"),
           qPrintable(h));
  // Cut inside the version line.
  QVERIFY(openError(none.substr(0, 8), "v.bag").startsWith("v.bag: offset 0: not a ROS 1 bag"));
}

void TstRosbag1::aRecordingCutShortKeepsItsCompleteChunks() {
  // small_chunks.bag cut 50 bytes into its last chunk (the 4th Range message): index_pos now
  // points past the end.
  const std::string b = readBytes(kDir + "small_chunks.bag").substr(0, kChunks[6] + 50);
  const auto r = open(b, "crash.bag");
  QCOMPARE(r->topics().size(), std::size_t{2});
  QCOMPARE(r->topics()[0].count, std::uint64_t{3});  // 3 of the 4 Range messages are whole
  QCOMPARE(r->topics()[0].lastNs, kT0 + 200 * kMs);
  QCOMPARE(r->topics()[1].count, std::uint64_t{3});
  std::size_t seen = 0;
  try {
    r->read({true, true}, {}, [&](const auto&) { ++seen; });
    QFAIL("a cut chunk was read");
  } catch (const BagError& e) {
    QCOMPARE(seen, std::size_t{6});  // the messages before the cut came first
    QCOMPARE(e.offset(), kChunks[6]);
    QCOMPARE(e.file(), std::string("crash.bag"));
    QVERIFY2(QString(e.what()).contains("cut short"), e.what());
  }
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{6});
  QCOMPARE(r->skipped().count, std::size_t{1});
  QVERIFY(QString::fromStdString(r->skipped().firstError).startsWith("crash.bag: offset 8723:"));
}

void TstRosbag1::aCorruptedChunkSizeIsAnError() {
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  {  // bz2: one byte more than the stream gives (the codec's error, rewrapped).
    std::string b = readBytes(kDir + "small_bz2.bag");
    const std::size_t at = valueOf(b, "size", kFirstChunk);
    put32(b, at, le32(b, at) + 1);
    const auto r = open(b, "bz2.bag");
    const QString e = strictError(*r);
    QVERIFY2(e.startsWith("bz2.bag: offset 4117: the bz2 chunk does not decompress to "),
             qPrintable(e));
    QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{0});
    QCOMPARE(r->skipped().count, std::size_t{1});
  }
  {  // none: the size must be the data length.
    std::string b = readBytes(kDir + "small_none.bag");
    const std::size_t at = valueOf(b, "size", kFirstChunk);
    const std::uint32_t size = le32(b, at);
    put32(b, at, size - 1);
    const QString e = strictError(*open(b, "none.bag"));
    QCOMPARE(e, QString("none.bag: offset 4117: an uncompressed chunk of %1 bytes declares a size "
                        "of %2")
                    .arg(size)
                    .arg(size - 1));
  }
  {  // A size past the limit is refused before anything is allocated.
    std::string b = readBytes(kDir + "small_lz4.bag");
    put32(b, valueOf(b, "size", kFirstChunk), 0xffffffffu);
    const QString e = strictError(*open(b, "huge.bag"));
    QVERIFY2(
        e.startsWith("huge.bag: offset 4117: the chunk declares 4294967295 uncompressed bytes"),
        qPrintable(e));
  }
}

void TstRosbag1::anUnknownCompressionIsNamed() {
  std::string b = readBytes(kDir + "small_lz4.bag");
  const std::size_t at = valueOf(b, "compression", kFirstChunk);
  QCOMPARE(b.substr(at, 3), std::string("lz4"));
  b.replace(at, 3, "zst");
  const auto r = open(b, "zst.bag");
  QCOMPARE(strictError(*r),
           QString("zst.bag: offset 4117: unknown chunk compression 'zst'; SonarGrid reads none, "
                   "bz2 and lz4"));
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;
  QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{0});
  QCOMPARE(r->skipped().count, std::size_t{1});
}

void TstRosbag1::badRecordsInsideAChunkNameTheChunkAndRecord() {
  // small_none.bag's chunk is stored as is: patch its second message record (the first /odom).
  const std::string good = readBytes(kDir + "small_none.bag");
  const std::size_t data = chunkData(good, kFirstChunk);
  const std::size_t first = good.find(kMessageOp, data);
  const std::size_t op = good.find(kMessageOp, first + 1);
  const std::size_t record = op - 4 - data;  // its header length is 4 bytes before its op field
  const QString where =
      QString("chunk at offset 4117, record at byte %1 of the chunk: ").arg(record);
  sg::bag::ReadOptions lenient;
  lenient.lenient = true;

  {  // A field without '=': "op=" becomes "op_".
    std::string b = good;
    b[op + 6] = '_';
    const auto r = open(b, "eq.bag");
    QCOMPARE(strictError(*r),
             "eq.bag: offset 4117: " + where + "a header field without '=' (\"op_\\x02\")");
    // Lenient: the one record is skipped, the chunk goes on.
    const std::vector<Got> got = readAll(*r, {}, lenient);
    QCOMPARE(got.size(), std::size_t{6});
    QCOMPARE(got[1].topic, std::size_t{0});  // the second Range message follows the first
    QCOMPARE(r->skipped().count, std::size_t{1});
  }
  {  // A missing field: "time" renamed; the connection is known, so is the topic.
    std::string b = good;
    const std::size_t time = b.find("time=", op);
    b[time + 1] = 'a';
    QCOMPARE(strictError(*open(b, "time.bag")),
             "time.bag: offset 4117 (topic /odom): " + where + "missing required field 'time'");
  }
  {  // An undeclared connection: conn 7.
    std::string b = good;
    put32(b, valueOf(b, "conn", op), 7);
    QCOMPARE(strictError(*open(b, "conn.bag")),
             "conn.bag: offset 4117: " + where +
                 "a message on connection 7, which no connection record declares");
  }
  {  // A header length past the end of the chunk: the rest of the chunk is lost.
    std::string b = good;
    put32(b, op - 4, 0x7fffffff);
    const auto r = open(b, "len.bag");
    const QString e = strictError(*r);
    QVERIFY2(e.startsWith("len.bag: offset 4117: " + where +
                          "a header of 2147483647 bytes runs "
                          "past the end of the chunk"),
             qPrintable(e));
    QCOMPARE(readAll(*r, {}, lenient).size(), std::size_t{1});  // the first Range message
    QCOMPARE(r->skipped().count, std::size_t{1});
  }
}

void TstRosbag1::aBadVersionLineOrBagHeaderStopsTheOpen() {
  const std::string good = readBytes(kDir + "small_none.bag");
  std::string v = good;
  v.replace(9, 3, "1.2");
  QCOMPARE(openError(v, "old.bag"),
           QString("old.bag: offset 0: ROS bag format 1.2 is not supported; SonarGrid reads "
                   "format 2.0"));
  QCOMPARE(openError("hello", "x.bag"),
           QString("x.bag: offset 0: not a ROS 1 bag: the file does not start with "
                   "\"#ROSBAG V2.0\""));
  // A garbage header length for the bag header: refused, not allocated.
  std::string h = good;
  put32(h, 13, 0xffffffffu);
  QVERIFY(
      openError(h, "h.bag").startsWith("h.bag: offset 13: a record header of 4294967295 bytes"));
  // The first record is not a bag header: its op byte says chunk.
  std::string o = good;
  o[valueOf(o, "op")] = 0x05;
  QCOMPARE(openError(o, "op.bag"),
           QString("op.bag: offset 13: the first record is op 0x05, not the bag header (0x03)"));
  // Lenient reads do not change that: the open itself throws.
  QVERIFY_THROWS_EXCEPTION(BagError, open(o, "op.bag"));
}

QTEST_GUILESS_MAIN(TstRosbag1)
#include "tst_rosbag1.moc"
