// SPDX-License-Identifier: BSD-3-Clause
// The one atomic file writer (core/sonargrid/base/atomic_file.h): the bytes arrive whole, no
// temporary file survives, a failure names the path and leaves the old file as it was, and
// writers and readers running at the same time only ever see an old or a new file.

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sonargrid/base/atomic_file.h"

namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writePlain(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Whether the whole of `text` is `literal` (matched as it is, whatever characters a path holds), a
// temporary file's suffix ".<16 hex digits>.tmp", then `tail` as it is. (QRegularExpression, not
// std::regex: GCC 12's std::regex warns of maybe-uninitialised members under the sanitizers.)
bool isTemporaryName(const std::string& text, const std::string& literal,
                     const std::string& tail = {}) {
  const QRegularExpression shape(QRegularExpression::anchoredPattern(
      QRegularExpression::escape(QString::fromStdString(literal)) + R"(\.[0-9a-f]{16}\.tmp)" +
      QRegularExpression::escape(QString::fromStdString(tail))));
  return shape.match(QString::fromStdString(text)).hasMatch();
}

// Everything in the folder, hidden files included: a leftover temporary would show here.
QStringList entries(const QString& folder) {
  return QDir(folder).entryList(QDir::AllEntries | QDir::NoDotAndDotDot | QDir::Hidden, QDir::Name);
}

// Bytes that identify their writer in every part: a header naming (writer, round) and a body of
// that header repeated, of a length that differs per write. A file mixed from two writes, or cut
// short, does not match `payloadValid`.
std::string payload(int writer, int round) {
  const std::string tag = "<" + std::to_string(writer) + ":" + std::to_string(round) + ">";
  // 40 kB to 110 kB: across the writer's 64 kB block, so that one write is several write() calls.
  const std::size_t size =
      40000 + static_cast<std::size_t>((writer * 7919 + round * 104729) % 70000);
  std::string s = std::to_string(size) + "\n";
  while (s.size() < size) s += tag;
  s.resize(size);
  return s;
}

bool payloadValid(const std::string& s) {
  const auto newline = s.find('\n');
  if (newline == std::string::npos) return false;
  const std::size_t size = std::stoul(s.substr(0, newline));
  if (s.size() != size) return false;
  const auto close = s.find('>', newline);
  if (close == std::string::npos) return false;
  const std::string tag = s.substr(newline + 1, close - newline);
  std::string expected = s.substr(0, newline + 1);
  while (expected.size() < size) expected += tag;
  expected.resize(size);
  return s == expected;
}

}  // namespace

class TstAtomicFile : public QObject {
  Q_OBJECT

 private slots:
  void writesBytes_data();
  void writesBytes();
  void streamingForm();
  void replacesOldFile();
  void failures_data();
  void failures();
  void unwritableFolder();
  void writeFailureKeepsOldFile();
  void producerExceptionPropagates();
  void keepsPermissions();
  void followsSymbolicLink();
  void longFileName();
  void temporaryNamesNeverCollide();
  void parallelWritersAndReaders();
  void appendFileGrowsByWholeRecords();
  void appendFileErrorsNameThePath();
};

void TstAtomicFile::writesBytes_data() {
  QTest::addColumn<QByteArray>("bytes");
  QTest::addRow("empty") << QByteArray();
  QTest::addRow("text") << QByteArray("sglog 1\nname \"room\"\n");
  QTest::addRow("binary, NUL and high bytes") << QByteArray("\x00\xff\x89PNG\r\n\x1a\n\x00", 10);
  // One byte less than, exactly and beyond the 64 KiB block: the buffered and direct paths.
  QTest::addRow("block - 1") << QByteArray(64 * 1024 - 1, 'a');
  QTest::addRow("block") << QByteArray(64 * 1024, 'b');
  QByteArray big(3 * 1024 * 1024 + 7, '\0');
  for (qsizetype i = 0; i < big.size(); ++i) big[i] = static_cast<char>((i * 131) % 251);
  QTest::addRow("3 MiB + 7") << big;
}

void TstAtomicFile::writesBytes() {
  QFETCH(QByteArray, bytes);
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("out.bin").toStdString();
  sg::writeFileAtomically(path, std::string_view(bytes.constData(), std::size_t(bytes.size())));
  QCOMPARE(QByteArray::fromStdString(readAll(path)), bytes);
  QCOMPARE(entries(dir.path()), QStringList{"out.bin"});
}

void TstAtomicFile::streamingForm() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("log.sglog").toStdString();
  std::string expected;
  sg::writeFileAtomically(path, [&expected](sg::FileSink& sink) {
    // Many small pieces (buffered), then one larger than the block (written directly), then small
    // again: the order on disk is the order written.
    for (int i = 0; i < 20000; ++i) {
      const std::string line = "r " + std::to_string(i) + "\n";
      sink << line;
      expected += line;
    }
    const std::string block(200000, 'x');
    sink.write(block);
    expected += block;
    sink << "end\n";
    expected += "end\n";
  });
  QCOMPARE(readAll(path), expected);
  QCOMPARE(entries(dir.path()), QStringList{"log.sglog"});
}

void TstAtomicFile::replacesOldFile() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("map.pgm").toStdString();
  writePlain(path, std::string(100000, 'z'));  // longer than the new file: nothing may survive
  sg::writeFileAtomically(path, std::string("new"));
  QCOMPARE(readAll(path), std::string("new"));
  QCOMPARE(entries(dir.path()), QStringList{"map.pgm"});
}

void TstAtomicFile::failures_data() {
  QTest::addColumn<QString>("target");  // relative to a fresh folder that holds "old.txt"
  QTest::addColumn<QString>("reason");  // %1 = the fresh folder
  QTest::addRow("missing folder") << "no/such/old.txt"
                                  << "directory '%1/no/such' does not exist";
  QTest::addRow("target is a directory") << "taken"
                                         << "it is a directory";
  QTest::addRow("folder is a file") << "old.txt/inside"
                                    << "'%1/old.txt' is not a directory";
  QTest::addRow("path ends in a slash") << "sub/"
                                        << "the path names a folder, not a file";
}

void TstAtomicFile::failures() {
  QFETCH(QString, target);
  QFETCH(QString, reason);
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  writePlain(dir.filePath("old.txt").toStdString(), "old contents\n");
  QVERIFY(QDir(dir.path()).mkdir("taken"));
  const QStringList before = entries(dir.path());
  const std::string path = dir.filePath(target).toStdString();
  reason.replace(QStringLiteral("%1"), dir.path());
  try {
    sg::writeFileAtomically(path, std::string("new contents\n"));
    QFAIL("the write succeeded");
  } catch (const sg::FileWriteError& e) {
    QCOMPARE(QString::fromStdString(e.path()), QString::fromStdString(path));
    QCOMPARE(QString::fromStdString(e.reason()), reason);
    QCOMPARE(QString(e.what()),
             QStringLiteral("cannot write '%1': %2").arg(QString::fromStdString(path), reason));
  }
  QCOMPARE(entries(dir.path()), before);
  QCOMPARE(readAll(dir.filePath("old.txt").toStdString()), std::string("old contents\n"));
  QVERIFY(QDir(dir.filePath("taken")).isEmpty());
}

void TstAtomicFile::unwritableFolder() {
  // A folder without write permission; root writes anywhere on a normal file system, so it gets
  // sysfs, which refuses new files to everyone.
  const bool root = ::geteuid() == 0;
  if (root && !QFileInfo(QStringLiteral("/sys/kernel")).isDir()) QSKIP("root, and no /sys");
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string folder = root ? std::string("/sys/kernel") : dir.path().toStdString();
  const std::string path = folder + "/old.txt";
  if (!root) {
    writePlain(path, "old contents\n");
    QVERIFY(::chmod(folder.c_str(), 0555) == 0);
  }
  const QStringList before = entries(QString::fromStdString(folder));
  std::string what;
  try {
    sg::writeFileAtomically(path, std::string("new contents\n"));
  } catch (const sg::FileWriteError& e) {
    what = e.what();
  }
  if (!root) ::chmod(folder.c_str(), 0755);
  // "cannot write 'P': cannot create the temporary file 'P.<16 hex>.tmp': Permission denied"
  QVERIFY2(isTemporaryName(what,
                           "cannot write '" + path + "': cannot create the temporary file '" + path,
                           "': " + std::string(std::strerror(EACCES))),
           what.c_str());
  QCOMPARE(entries(QString::fromStdString(folder)), before);
  if (!root) QCOMPARE(readAll(path), std::string("old contents\n"));
}

void TstAtomicFile::writeFailureKeepsOldFile() {
  // A file size limit makes write() fail part-way (EFBIG), as a full disk would (ENOSPC).
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("old.txt").toStdString();
  writePlain(path, "old contents\n");
  struct rlimit saved {};
  QVERIFY(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
  struct rlimit small = saved;
  small.rlim_cur = 100000;
  const auto previous = ::signal(SIGXFSZ, SIG_IGN);  // else the process is killed
  QVERIFY(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string what;
  try {
    sg::writeFileAtomically(path, std::string(300000, 'n'));
  } catch (const sg::FileWriteError& e) {
    what = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous);
  QVERIFY2(
      isTemporaryName(what, "cannot write '" + path + "': cannot write the temporary file '" + path,
                      "': " + std::string(std::strerror(EFBIG))),
      what.c_str());
  QCOMPARE(readAll(path), std::string("old contents\n"));
  QCOMPARE(entries(dir.path()), QStringList{"old.txt"});
}

void TstAtomicFile::producerExceptionPropagates() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("old.txt").toStdString();
  writePlain(path, "old contents\n");
  try {
    sg::writeFileAtomically(path, [](sg::FileSink& sink) {
      sink.write(std::string(200000, 'p'));  // already on disk in the temporary file
      throw std::logic_error("scan 3 is out of order");
    });
    QFAIL("the write succeeded");
  } catch (const std::logic_error& e) {
    QCOMPARE(std::string(e.what()), std::string("scan 3 is out of order"));
  }
  QCOMPARE(readAll(path), std::string("old contents\n"));
  QCOMPARE(entries(dir.path()), QStringList{"old.txt"});
}

void TstAtomicFile::keepsPermissions() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("private.sglog").toStdString();
  writePlain(path, "old");
  QVERIFY(::chmod(path.c_str(), 0600) == 0);
  sg::writeFileAtomically(path, std::string("new"));
  struct stat st {};
  QVERIFY(::stat(path.c_str(), &st) == 0);
  QCOMPARE(st.st_mode & 07777, mode_t{0600});
  QCOMPARE(readAll(path), std::string("new"));
}

void TstAtomicFile::followsSymbolicLink() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  QVERIFY(QDir(dir.path()).mkdir("real"));
  const std::string real = dir.filePath("real/map.yaml").toStdString();
  const std::string link = dir.filePath("map.yaml").toStdString();
  writePlain(real, "old");
  QVERIFY(::symlink(real.c_str(), link.c_str()) == 0);
  sg::writeFileAtomically(link, std::string("new"));
  QVERIFY(QFileInfo(QString::fromStdString(link)).isSymLink());
  QCOMPARE(readAll(real), std::string("new"));
  QCOMPARE(entries(dir.filePath("real")), QStringList{"map.yaml"});
  QCOMPARE(entries(dir.path()), (QStringList{"map.yaml", "real"}));
}

void TstAtomicFile::longFileName() {
  // 250 bytes: legal, but with ".<16 hex>.tmp" appended it would pass the 255-byte limit.
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const QString name = QString(246, 'n') + ".png";
  const std::string path = dir.filePath(name).toStdString();
  sg::writeFileAtomically(path, std::string("png"));
  QCOMPARE(readAll(path), std::string("png"));
  QCOMPARE(entries(dir.path()), QStringList{name});
  const std::string temporary = sg::temporarySiblingName(path);
  QCOMPARE(QFileInfo(QString::fromStdString(temporary)).fileName().size(), 255);
}

void TstAtomicFile::temporaryNamesNeverCollide() {
  // 8 threads x 50 names at once, as 8 writers of one target would draw them.
  constexpr int kThreads = 8;
  constexpr int kPerThread = 50;
  const std::string path = "/data/run/room.sglog";
  std::vector<std::vector<std::string>> drawn(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&drawn, &path, t] {
      for (int i = 0; i < kPerThread; ++i) drawn[t].push_back(sg::temporarySiblingName(path));
    });
  for (std::thread& t : threads) t.join();
  std::set<std::string> unique;
  for (const auto& names : drawn)
    for (const std::string& n : names) {
      QVERIFY2(isTemporaryName(n, path), n.c_str());
      unique.insert(n);
    }
  QCOMPARE(unique.size(), std::size_t{kThreads * kPerThread});
}

void TstAtomicFile::parallelWritersAndReaders() {
  // 8 writers x 50 writes of distinct payloads to one target while 2 readers read it over and
  // over: every write succeeds, every read is one whole payload (never a mix or a prefix), and
  // the final file is one of the payloads with no temporary file left.
  constexpr int kWriters = 8;
  constexpr int kRounds = 50;
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("shared.bin").toStdString();
  sg::writeFileAtomically(path, payload(kWriters, 0));  // no writer's: replaced in the end

  std::atomic<int> writersLeft{kWriters};
  std::atomic<int> failures{0};
  std::atomic<int> badReads{0};
  std::atomic<int> reads{0};
  std::vector<std::string> errors(kWriters);
  std::vector<std::thread> threads;
  for (int w = 0; w < kWriters; ++w)
    threads.emplace_back([&, w] {
      for (int r = 0; r < kRounds; ++r) {
        try {
          sg::writeFileAtomically(path, payload(w, r));
        } catch (const std::exception& e) {
          ++failures;
          errors[w] = e.what();
        }
      }
      --writersLeft;
    });
  for (int k = 0; k < 2; ++k)
    threads.emplace_back([&] {
      while (writersLeft.load() > 0) {
        if (!payloadValid(readAll(path))) ++badReads;
        ++reads;
      }
    });
  for (std::thread& t : threads) t.join();

  for (const std::string& e : errors) QVERIFY2(e.empty(), e.c_str());
  QCOMPARE(failures.load(), 0);
  QCOMPARE(badReads.load(), 0);
  QVERIFY(reads.load() > 0);
  const std::string last = readAll(path);
  QVERIFY(payloadValid(last));
  QVERIFY(last != payload(kWriters, 0));
  QCOMPARE(entries(dir.path()), QStringList{"shared.bin"});
}

// AppendFile (the recorder's scans, the sweep's rows): Empty starts the file again, AtEnd adds to
// what is there; every record is in the file as soon as append() returns (another reader sees it,
// as a process killed then would leave it), sync() and close() report nothing on a good file.
void TstAtomicFile::appendFileGrowsByWholeRecords() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("rows.csv").toStdString();
  {
    sg::AppendFile f(path, sg::AppendFile::Start::Empty);  // created
    QVERIFY(f.isOpen());
    QCOMPARE(f.path(), path);
    f.append("a,1\n");
    QCOMPARE(readAll(path), std::string("a,1\n"));
    f.sync();
    f.append("b,2\n");
    QCOMPARE(readAll(path), std::string("a,1\nb,2\n"));
    f.close();
    QVERIFY(!f.isOpen());
    f.close();  // nothing more to do
  }
  {
    sg::AppendFile f(path, sg::AppendFile::Start::AtEnd);  // a resumed sweep
    f.append("c,3\n");
    f.sync();
  }  // closed by the destructor
  QCOMPARE(readAll(path), std::string("a,1\nb,2\nc,3\n"));
  {
    sg::AppendFile f(path, sg::AppendFile::Start::Empty);  // a new recording over an old one
    f.append("x\n");
  }
  QCOMPARE(readAll(path), std::string("x\n"));
  const std::string fresh = dir.filePath("fresh.csv").toStdString();
  {
    sg::AppendFile f(fresh, sg::AppendFile::Start::AtEnd);  // created when missing
    f.append("first\n");
    f.sync();  // syncs the new file's folder too
  }
  QCOMPARE(readAll(fresh), std::string("first\n"));
  QCOMPARE(entries(dir.path()), (QStringList{"fresh.csv", "rows.csv"}));  // no temporary files
}

void TstAtomicFile::appendFileErrorsNameThePath() {
  try {
    sg::AppendFile f("/nonexistent-dir/rows.csv", sg::AppendFile::Start::AtEnd);
    QFAIL("a file in a missing folder opened");
  } catch (const sg::FileWriteError& e) {
    QCOMPARE(QString(e.what()), QString("cannot write '/nonexistent-dir/rows.csv': ") +
                                    QString::fromStdString(std::strerror(ENOENT)));
  }
  QTemporaryDir dir;
  const std::string path = dir.filePath("closed.csv").toStdString();
  sg::AppendFile f(path, sg::AppendFile::Start::Empty);
  f.close();
  try {
    f.append("late\n");
    QFAIL("a closed file took a record");
  } catch (const sg::FileWriteError& e) {
    QCOMPARE(QString(e.what()),
             QString::fromStdString("cannot write '" + path + "': the file is closed"));
  }
  // A record the file size limit cuts (as a full disk would): the error names the file and why.
  struct rlimit saved {};
  QVERIFY(::getrlimit(RLIMIT_FSIZE, &saved) == 0);
  struct rlimit small = saved;
  small.rlim_cur = 1000;
  const auto previous = ::signal(SIGXFSZ, SIG_IGN);
  std::string what;
  {
    sg::AppendFile big(dir.filePath("big.csv").toStdString(), sg::AppendFile::Start::Empty);
    big.append(std::string(900, 'a'));
    QVERIFY(::setrlimit(RLIMIT_FSIZE, &small) == 0);
    try {
      big.append(std::string(300, 'b'));
    } catch (const sg::FileWriteError& e) {
      what = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &saved);
  }
  ::signal(SIGXFSZ, previous);
  QCOMPARE(QString::fromStdString(what),
           QString::fromStdString("cannot write '" + dir.filePath("big.csv").toStdString() +
                                  "': " + std::strerror(EFBIG)));
}

QTEST_GUILESS_MAIN(TstAtomicFile)
#include "tst_atomic_file.moc"
