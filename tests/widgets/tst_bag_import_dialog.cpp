// SPDX-License-Identifier: GPL-3.0-or-later
// The ROS bag dialog offscreen, on the room log's bags (tests/data/bags/room/README.md: written by
// npm's @mcap/core and by Debian's python3-rosbag from datasets/room/room.sglog): every topic with
// its type, count and rate; the picks pre-selected; a preview of the first 10 s read by the core;
// and the options it gives load what readLog loads with the same topics.

#include <QComboBox>
#include <QPushButton>
#include <QTableWidget>
#include <QtTest>

#include "bag_import_dialog.h"
#include "sonargrid/io/log_reader.h"

using namespace sg;
using Column = ui::BagImportDialog::Column;

namespace {

const QString kBags = QStringLiteral(SONARGRID_TEST_DATA "/bags/room/");

int rowOf(const QTableWidget* t, const QString& topic) {
  for (int r = 0; r < t->rowCount(); ++r)
    if (t->item(r, Column::Name)->text() == topic) return r;
  return -1;
}

QString text(const QTableWidget* t, int row, int column) {
  return t->item(row, column)->text();
}

}  // namespace

class TstBagImportDialog : public QObject {
  Q_OBJECT

 private slots:
  void topicsAreListedWithThePicksChosen() {
    const QString path = kBags + QStringLiteral("room-zstd.mcap");
    ui::BagImportDialog d(path, bag::inspectBag(path.toStdString()));
    const QTableWidget* t = d.topicTable();
    // The README's counts: 1 /tf_static, 743 /odom, 743 /ground_truth, 11 888 /sonar.
    QCOMPARE(t->rowCount(), 4);
    const int sonar = rowOf(t, QStringLiteral("/sonar"));
    const int odom = rowOf(t, QStringLiteral("/odom"));
    const int truth = rowOf(t, QStringLiteral("/ground_truth"));
    const int tf = rowOf(t, QStringLiteral("/tf_static"));
    QVERIFY(sonar >= 0 && odom >= 0 && truth >= 0 && tf >= 0);
    QCOMPARE(text(t, sonar, Column::Type), QStringLiteral("sensor_msgs/Range"));
    QCOMPARE(text(t, odom, Column::Type), QStringLiteral("nav_msgs/Odometry"));
    QCOMPARE(text(t, sonar, Column::Count), QStringLiteral("11888"));
    QCOMPARE(text(t, odom, Column::Count), QStringLiteral("743"));
    // Rate = (count - 1) / (last - first log time): 742 odometry intervals over 74.2 s is 10 Hz;
    // 16 readings per scan stamped with it, 11 887 / 74.2 = 160.2 Hz; one /tf_static has none.
    QCOMPARE(text(t, odom, Column::Rate), QStringLiteral("10.0"));
    QCOMPARE(text(t, sonar, Column::Rate), QStringLiteral("160.2"));
    QCOMPARE(text(t, tf, Column::Rate), QStringLiteral("—"));
    // The picks, pre-selected: only a sonar-capable topic has a box.
    QCOMPARE(t->item(sonar, Column::Sonar)->checkState(), Qt::Checked);
    QVERIFY(!(t->item(odom, Column::Sonar)->flags() & Qt::ItemIsUserCheckable));
    QVERIFY(d.previewParses());
    // 101 scans of 16 readings in [0, 10] s (a scan every 0.1 s), all with a true pose.
    QCOMPARE(d.result(), QStringLiteral("101 scans, 1616 readings in the first 10 s; 16 sonars "
                                        "(p3dx), with true poses"));
    QCOMPARE(d.previewTable()->rowCount(), ui::BagImportDialog::kPreviewScans);
    // The first scan as the .sglog has it: time 0, its odometry.
    const Dataset full = readLog(path.toStdString());
    const Scan& first = full.scans.front();
    QCOMPARE(text(d.previewTable(), 0, 0), QStringLiteral("0.000"));
    QCOMPARE(text(d.previewTable(), 0, 1), QString::number(first.odometry.x(), 'f', 3));
    QCOMPARE(text(d.previewTable(), 0, 4), QStringLiteral("16"));
    const std::optional<LogOptions> o = d.options();
    QVERIFY(o.has_value());
    QCOMPARE(o->format, LogFormat::Bag);
    QCOMPARE(o->topics.sonar, std::vector<std::string>{"/sonar"});
    QCOMPARE(o->topics.odometry, std::string("/odom"));
    QCOMPARE(o->topics.truth, std::string("/ground_truth"));
    QVERIFY(!o->ring.has_value());
    QVERIFY(readLog(path.toStdString(), *o) == full);
    QVERIFY(d.findChild<QPushButton*>() != nullptr);
  }

  void noTruthAndNoSonarAreChoicesToo() {
    const QString path = kBags + QStringLiteral("room-none.bag");
    ui::BagImportDialog d(path, bag::inspectBag(path.toStdString()));
    d.setTruth(QString());
    QVERIFY(d.previewParses());
    QVERIFY(d.result().endsWith(QStringLiteral("(p3dx)")));  // no true poses now
    QCOMPARE(d.options()->topics.truth, std::string("-"));
    const Dataset withoutTruth = readLog(path.toStdString(), *d.options());
    QVERIFY(!withoutTruth.hasTruth());
    QCOMPARE(withoutTruth.scans.size(), std::size_t{743});
    d.setSonar(QStringLiteral("/sonar"), false);
    QVERIFY(!d.previewParses());
    QVERIFY(!d.options().has_value());
    QCOMPARE(d.result(), QStringLiteral("Tick at least one sonar topic."));
  }

  void aRosAriaBagAsksForItsRing() {
    // RosAria's point clouds carry no sonar geometry: the preview says so until a ring is chosen.
    const QString path = kBags + QStringLiteral("rosaria-room.bag");
    ui::BagImportDialog d(path, bag::inspectBag(path.toStdString()));
    QVERIFY(!d.previewParses());
    QVERIFY2(d.result().startsWith(QStringLiteral("Choose the robot under Sonar ring")),
             qPrintable(d.result()));
    QVERIFY2(d.result().contains(QStringLiteral("rosaria-room.bag")), qPrintable(d.result()));
    QVERIFY(!d.options().has_value());
    d.setRobotPreset(QStringLiteral("p3dx"));
    QVERIFY2(d.previewParses(), qPrintable(d.result()));
    QVERIFY(d.result().startsWith(QStringLiteral("101 scans, 1616 readings")));
    const LogOptions o = *d.options();
    QVERIFY(o.ring == SonarRing::pioneer3dx());
    QCOMPARE(o.topics.sonar, std::vector<std::string>{"/RosAria/sonar"});
    QCOMPARE(o.topics.odometry, std::string("/RosAria/pose"));
    LogOptions cli;
    cli.ring = SonarRing::pioneer3dx();  // sonargrid-cli --robot p3dx
    QVERIFY(readLog(path.toStdString(), o) == readLog(path.toStdString(), cli));
  }

  void anEarlierChoiceIsShownAgain() {
    const QString path = kBags + QStringLiteral("room-lz4.mcap");
    LogOptions earlier;
    earlier.topics.truth = "-";
    earlier.ring = SonarRing::amigobot();
    ui::BagImportDialog d(path, bag::inspectBag(path.toStdString()), earlier);
    const std::optional<LogOptions> o = d.options();
    QVERIFY2(o.has_value(), qPrintable(d.result()));
    QCOMPARE(o->topics.truth, std::string("-"));
    QCOMPARE(o->ring->robot, std::string("amigobot"));
    QCOMPARE(o->topics.sonar, std::vector<std::string>{"/sonar"});  // the pick: none was given
  }
};

QTEST_MAIN(TstBagImportDialog)
#include "tst_bag_import_dialog.moc"
