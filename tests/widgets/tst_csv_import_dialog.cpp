// SPDX-License-Identifier: GPL-3.0-or-later
// The CSV import dialog offscreen: the roles, units, no-echo value and geometry chosen through its
// API write the --columns spec docs/formats.md documents for tests/data/logs/mm_ddeg.csv, and the
// options it builds load the same Dataset as readLog with that spec; bad choices show the first
// error with its line and field.

#include <QTableWidget>
#include <QtTest>

#include "csv_import_dialog.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"

using namespace sg;
using Role = ui::CsvImportDialog::Role;

namespace {

const QString kCsv = QStringLiteral(SONARGRID_TEST_DATA "/logs/mm_ddeg.csv");
const QString kGeometry = QStringLiteral(SONARGRID_TEST_DATA "/logs/ring4_mm.geom");
// docs/formats.md, "CSV and text columns": the spec the sample is read with.
const QString kDocumentedSpec =
    QStringLiteral("header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,noecho=5110");

// The fixture's choices, made the way a user makes them: header row, roles, units, ring.
void chooseFixtureMapping(ui::CsvImportDialog& d) {
  d.setHeaderLines(1);
  for (int c = 0; c < d.columnCount(); ++c) d.setRole(c, Role::Ignore);
  d.setRole(0, Role::Time);
  d.setRole(1, Role::X);
  d.setRole(2, Role::Y);
  d.setRole(3, Role::Theta);
  for (int k = 0; k < 4; ++k) d.setRole(4 + k, Role::Sonar, k);
  d.setLengthUnit(LengthUnit::Millimetre);
  d.setAngleUnit(AngleUnit::TenthDegree);
  d.setNoEcho(QStringLiteral("5110"));
  d.setGeometryFile(kGeometry);
}

}  // namespace

class TestCsvImportDialog : public QObject {
  Q_OBJECT

 private slots:
  void previewShowsTheFirstRows() {
    ui::CsvImportDialog d(kCsv);
    // mm_ddeg.csv: a header row and 3 data rows of 8 comma-separated columns; the table's first
    // row holds the role choosers.
    QCOMPARE(d.columnCount(), 8);
    // Its first row holds names over rows of numbers: taken for a header.
    QVERIFY(d.columnSpec().startsWith(QStringLiteral("header=1,")));
    QCOMPARE(d.previewTable()->rowCount(), 1 + 4);
    QCOMPARE(d.previewTable()->item(2, 4)->text(), QStringLiteral("1500"));
    QCOMPARE(d.previewTable()->item(4, 3)->text(), QStringLiteral("900"));
  }

  void rolesWriteTheCliSpecAndLoadTheSameDataset() {
    ui::CsvImportDialog d(kCsv);
    chooseFixtureMapping(d);
    QCOMPARE(d.columnSpec(), kDocumentedSpec);
    QVERIFY2(d.previewParses(), qPrintable(d.result()));
    // 3 data rows, one reading per sonar column each (no-echo readings included): 3 scans, 12.
    QVERIFY2(d.result().contains(QStringLiteral("3 scans, 12 readings")), qPrintable(d.result()));

    LogOptions cli;  // what `--columns SPEC --robot ring4_mm.geom` gives (app/cli/log_flags.cpp)
    cli.csv = parseCsvLayout(kDocumentedSpec.toStdString());
    cli.ring = readSonarGeometry(kGeometry.toStdString());
    const Dataset expected = readLog(kCsv.toStdString(), cli);
    QVERIFY(d.options().has_value());
    const Dataset got = readLog(kCsv.toStdString(), *d.options());
    QVERIFY(got == expected);
    QCOMPARE(got.scans.size(), std::size_t(3));
    // Row 2 of the file: x = 1000 mm, sonar 1 reads 5110 = no echo.
    QCOMPARE(got.scans[0].odometry.x(), 1.0);
    QVERIFY(!got.scans[0].readings[1].echo());
  }

  void sonarRunsAndOtherUnitsInTheSpec() {
    ui::CsvImportDialog d(kCsv);
    chooseFixtureMapping(d);
    // Sonars in columns 8, 5, 6, 7: two runs in ring order.
    d.setRole(7, Role::Sonar, 0);
    d.setRole(4, Role::Sonar, 1);
    d.setRole(5, Role::Sonar, 2);
    d.setRole(6, Role::Sonar, 3);
    d.setRangeUnit(LengthUnit::Centimetre);
    d.setTimeUnit(QStringLiteral("ms"));
    d.setDelimiter(',');
    d.setRobotPreset(QStringLiteral("p3dx"));
    QCOMPARE(d.columnSpec(),
             QStringLiteral("header=1,time=1,x=2,y=3,theta=4,sonars=8,sonars=5-7,length=mm,"
                            "range=cm,angle=ddeg,time_unit=ms,noecho=5110,delimiter=comma"));
    // The p3dx ring has 16 sonars, the rows 4: the core says so.
    QVERIFY(!d.previewParses());
    QVERIFY(!d.options().has_value());
  }

  void posesFromASecondFile() {
    // tests/data/logs/ranges_only.txt: "time s0 s1 s2 s3" rows separated by blanks, a # comment.
    const QString log = QStringLiteral(SONARGRID_TEST_DATA "/logs/ranges_only.txt");
    ui::CsvImportDialog d(log);
    QCOMPARE(d.columnCount(), 5);
    d.setRole(0, Role::Time);
    for (int k = 0; k < 4; ++k) d.setRole(1 + k, Role::Sonar, k);
    d.setGeometryFile(kGeometry);
    d.setPosesFile(QStringLiteral(SONARGRID_TEST_DATA "/logs/poses.txt"));
    QCOMPARE(d.columnSpec(), QStringLiteral("time=1,sonars=2-5"));
    QVERIFY2(d.previewParses(), qPrintable(d.result()));
    const Dataset got = readLog(log.toStdString(), *d.options());
    QCOMPARE(got.scans.size(), std::size_t(3));
    // t = 0.25, halfway between the poses (0, 0, 0) at 0 and (1, 0, 0.5) at 0.5 of poses.txt.
    QCOMPARE(got.scans[0].odometry.x(), 0.5);
    QCOMPARE(got.scans[0].odometry.heading, 0.25);
  }

  void errorsNameTheLineAndField() {
    ui::CsvImportDialog d(kCsv);
    chooseFixtureMapping(d);
    d.setHeaderLines(0);  // the header row is now read as data: line 1, the time column
    QVERIFY(!d.previewParses());
    QVERIFY2(d.result().contains(QStringLiteral("mm_ddeg.csv:1:")), qPrintable(d.result()));
    QVERIFY2(d.result().contains(QStringLiteral("column 1")), qPrintable(d.result()));

    d.setHeaderLines(1);
    QVERIFY(d.previewParses());
    d.setRole(5, Role::Sonar, 0);  // sonar 0 twice, sonar 1 nowhere
    QVERIFY(!d.previewParses());
    QCOMPARE(d.result(), QStringLiteral("Error: sonar 0 is given to columns 5 and 6"));
    d.setRole(5, Role::Ignore);
    QCOMPARE(d.result(),
             QStringLiteral("Error: sonar 1 has no column (sonars are numbered from 0)"));
  }
};

QTEST_MAIN(TestCsvImportDialog)
#include "tst_csv_import_dialog.moc"
