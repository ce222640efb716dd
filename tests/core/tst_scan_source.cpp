// SPDX-License-Identifier: BSD-3-Clause
// The scan source: a loaded log is a complete source; appended scans extend it; a prefix taken
// earlier never changes; out-of-order scans and appends after the end are refused; and a reader
// on another thread always sees whole scans in order while a writer appends.

#include <QtTest>
#include <atomic>
#include <memory>
#include <thread>

#include "sonargrid/engine/scan_source.h"

using namespace sg;

namespace {

// Scan k at t = 0.1 k with two readings whose ranges name it (k + 0.25, k + 0.5): a reader can
// tell from any scan whether it is whole and in its place.
Scan scanNumber(int k) {
  Scan s;
  s.time = 0.1 * k;
  s.odometry = Pose2D(0.01 * k, 0.0, 0.0);
  s.readings = {Reading{0, k + 0.25, s.time}, Reading{1, k + 0.5, s.time + 0.01}};
  return s;
}

std::vector<Scan> scans(int from, int to) {
  std::vector<Scan> out;
  for (int k = from; k < to; ++k) out.push_back(scanNumber(k));
  return out;
}

bool isScan(const Scan& s, int k) {
  return s == scanNumber(k);
}

}  // namespace

class TstScanSource : public QObject {
  Q_OBJECT

 private slots:
  void loadedLogIsComplete();
  void appendExtendsWithoutChangingPrefixes();
  void spansCrossChunks();
  void refusals();
  void readingOrder();
  void readerSeesWholeScansWhileAWriterAppends();
  void viewIsTheCompleteLog();
};

void TstScanSource::loadedLogIsComplete() {
  Dataset d;
  d.name = "log";
  d.ring = SonarRing::pioneer3dx();
  d.scans = scans(0, 5);
  const ScanSource source(d);
  QVERIFY(source.complete());
  QCOMPARE(source.size(), std::size_t{5});
  QCOMPARE(source.name(), std::string("log"));
  QVERIFY(source.ring() == d.ring);
  const ScanPrefix p = source.prefix();
  QVERIFY(p.complete());
  for (int k = 0; k < 5; ++k) QVERIFY(isScan(p[static_cast<std::size_t>(k)], k));
  QVERIFY_THROWS_EXCEPTION(std::out_of_range, p[5]);
  QVERIFY(source.dataset(5) == d);
  QCOMPARE(source.dataset(2).scans.size(), std::size_t{2});
  QVERIFY(ScanSource(Dataset{}).prefix().empty());
}

void TstScanSource::appendExtendsWithoutChangingPrefixes() {
  ScanSource source("live", SonarRing::pioneer3dx());
  QVERIFY(!source.complete());
  QVERIFY(source.prefix().empty());
  source.append(scans(0, 3));
  const ScanPrefix first = source.prefix();
  source.append(scans(3, 4));
  source.append({});  // nothing: no change
  source.append(scans(4, 10));
  const ScanPrefix second = source.prefix();
  QCOMPARE(first.size(), std::size_t{3});
  QCOMPARE(second.size(), std::size_t{10});
  for (int k = 0; k < 3; ++k) QVERIFY(isScan(first[static_cast<std::size_t>(k)], k));
  for (int k = 0; k < 10; ++k) QVERIFY(isScan(second[static_cast<std::size_t>(k)], k));
  QVERIFY(!second.complete());
  source.finish();
  QVERIFY(source.complete());
  QVERIFY(source.prefix().complete());
  QVERIFY(!second.complete());  // as it was when taken
}

void TstScanSource::spansCrossChunks() {
  // 600 scans appended one at a time merge into chunks of at least 512 before a new one starts;
  // then a batch of 1000 is a chunk of its own. Spans of any range cover exactly that range, in
  // order.
  ScanSource source("live", SonarRing::pioneer3dx());
  for (int k = 0; k < 600; ++k) source.append(scans(k, k + 1));
  source.append(scans(600, 1600));
  const ScanPrefix p = source.prefix();
  QCOMPARE(p.size(), std::size_t{1600});
  for (const auto& [from, to] : std::vector<std::pair<std::size_t, std::size_t>>{
           {0, 1600}, {0, 1}, {511, 513}, {599, 601}, {1000, 1600}, {5, 5}, {1500, 5000}}) {
    std::size_t k = from;
    const auto spans = p.spans(from, to);
    for (const std::span<const Scan>& s : spans)
      for (const Scan& scan : s) QVERIFY(isScan(scan, static_cast<int>(k++)));
    QCOMPARE(k, std::min(to, p.size()));
    QCOMPARE(p.copy(from, to).size(), std::min(to, p.size()) - std::min(from, to));
  }
  QVERIFY(p.spans(0, 1600).size() <= 3);  // few chunks, not 600
}

void TstScanSource::refusals() {
  ScanSource source("live", SonarRing::pioneer3dx());
  source.append(scans(0, 5));
  // A batch with a scan before the last one is refused whole.
  std::vector<Scan> late = scans(5, 7);
  late.push_back(scanNumber(2));
  try {
    source.append(late);
    QFAIL("an out-of-order scan was accepted");
  } catch (const ScanSourceError& e) {
    QVERIFY2(std::string(e.what()).find("time order") != std::string::npos, e.what());
  }
  QCOMPARE(source.size(), std::size_t{5});
  source.append(scans(5, 6));  // and the source goes on from where it was
  QCOMPARE(source.size(), std::size_t{6});
  source.finish();
  QVERIFY_THROWS_EXCEPTION(ScanSourceError, source.append(scans(6, 7)));
  QCOMPARE(source.size(), std::size_t{6});
}

void TstScanSource::readingOrder() {
  // Scans in time order whose readings are not (a reading stamped before the previous scan's).
  ScanSource source("live", SonarRing::pioneer3dx());
  source.append(scans(0, 3));
  QVERIFY(source.prefix().readingsInTimeOrder());
  Scan odd = scanNumber(3);
  odd.readings[0].time = 0.05;
  source.append({odd});
  QVERIFY(!source.prefix().readingsInTimeOrder());
  Dataset d;
  d.scans = scans(0, 3);
  QVERIFY(ScanSource(d).prefix().readingsInTimeOrder());
  d.scans.push_back(odd);
  QVERIFY(!ScanSource(d).prefix().readingsInTimeOrder());
}

void TstScanSource::readerSeesWholeScansWhileAWriterAppends() {
  // A writer appends 3000 scans in batches of 1 to 7 while this thread takes prefixes and reads
  // them: every prefix is whole scans 0 .. n − 1 in order, n never shrinks, and the last prefix
  // (taken after finish()) has them all. (CI runs the core tests under TSan as well.)
  auto source = std::make_shared<ScanSource>("live", SonarRing::pioneer3dx());
  std::thread writer([source] {
    int k = 0;
    for (int batch = 1; k < 3000; batch = batch % 7 + 1) {
      const int to = std::min(3000, k + batch);
      source->append(scans(k, to));
      k = to;
    }
    source->finish();
  });
  std::size_t seen = 0;
  int reads = 0;
  for (;;) {
    const bool done = source->complete();
    const ScanPrefix p = source->prefix();
    QVERIFY(p.size() >= seen);
    for (std::size_t i = seen; i < p.size(); ++i) QVERIFY(isScan(p[i], static_cast<int>(i)));
    seen = p.size();
    ++reads;
    if (done) break;
  }
  writer.join();
  QCOMPARE(seen, std::size_t{3000});
  QVERIFY(reads >= 1);
}

void TstScanSource::viewIsTheCompleteLog() {
  // A loaded log shared with its source: the source reads the log's own scans (no copy) and its
  // view is the log itself, the same object each time.
  Dataset d;
  d.name = "log";
  d.ring = SonarRing::pioneer3dx();
  d.scans = scans(0, 4);
  const auto log = std::make_shared<const Dataset>(d);
  const ScanSource loaded(log);
  QVERIFY(loaded.complete());
  QCOMPARE(loaded.size(), std::size_t{4});
  QCOMPARE(&loaded.prefix()[2], &log->scans[2]);
  QCOMPARE(loaded.view().get(), log.get());
  QVERIFY(ScanSource(std::shared_ptr<const Dataset>()).view()->scans.empty());

  // A live source: the scans so far, copied once per growth.
  ScanSource live("live", SonarRing::pioneer3dx());
  QVERIFY(live.view()->scans.empty());
  live.append(scans(0, 3));
  const auto first = live.view();
  QCOMPARE(first->scans.size(), std::size_t{3});
  QVERIFY(*first == live.dataset(3));
  QCOMPARE(live.view().get(), first.get());  // nothing came: the same view
  live.append(scans(3, 5));
  const auto second = live.view();
  QCOMPARE(second->scans.size(), std::size_t{5});
  QVERIFY(isScan(second->scans[4], 4));
  QCOMPARE(first->scans.size(), std::size_t{3});  // a view taken before is never changed
}

QTEST_GUILESS_MAIN(TstScanSource)
#include "tst_scan_source.moc"
