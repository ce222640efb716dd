// SPDX-License-Identifier: GPL-3.0-or-later
// The project file (docs/formats.md, "Project file") without a window: every field of a
// ProjectState survives a save and a read, paths are stored relative to the project, and a corrupt
// file is refused with an error naming the file and the line or field.

#include <QDir>
#include <QTemporaryDir>
#include <QtTest>

#include "project_file.h"
#include "sonargrid/reference/reference_json.h"

using namespace sg;
using namespace sg::app;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");
const QString kRoomReference = QStringLiteral(SONARGRID_DATASETS "/room/room.json");

MapperSettings settingsOf(const std::string& model, const std::string& rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  return s;
}

// A state in which every field differs from its default, so a field that is not saved or not
// read back shows as a difference.
ProjectState everyFieldSet(const QString& dir) {
  ProjectState s;
  s.logPath = QFileInfo(kRoom).absoluteFilePath();
  s.logReading.format = LogFormat::Csv;
  s.logReading.lenient = true;
  s.logReading.ring = SonarRing::k2a(0.25);
  s.logReading.ring->sonars[3].pose.heading = 0.1;  // a ring no preset has
  s.logReading.csv = parseCsvLayout("time=1,x=2,y=3,theta=4,sonars=5-28,length=mm,noecho=5110");
  s.logReading.posesPath = dir + QStringLiteral("/poses.csv");
  s.logReading.topics = {{"/sonar/front", "/sonar/back"}, "/odom", "-"};
  s.logReading.startPose = Pose2D(2.25, -1.0, degToRad(-37.5));  // an angle with a long decimal
  s.secondLogPath =
      QFileInfo(QStringLiteral(SONARGRID_DATASETS "/arafat-room/run-2.sglog")).absoluteFilePath();
  ReferenceMap ref;
  ref.unit = LengthUnit::Centimetre;
  ReferenceObject box;
  box.name = "box";
  box.closed = true;
  box.corners = {{10.0, 20.0}, {110.0, 20.0}, {110.0, 70.5}, {10.0, 70.5}};
  ReferenceObject wall;
  wall.name = "wall";
  wall.closed = false;
  wall.corners = {{-50.0, 0.0}, {-50.0, 300.0}};
  ref.objects = {box, wall};
  s.reference = ref;
  s.referencePath = dir + QStringLiteral("/drawn.json");  // edited since: held inline
  s.referenceModified = true;
  s.settings = settingsOf("parameterized", "bayes");
  s.settings.parameters.set("p2", 0.15);
  s.settings.parameters.set("p5", 17.0);
  s.settings.pose = PoseSource::Truth;
  s.cellSize = 0.07;
  s.overlays = ui::Overlays(ui::Overlay::Reference) | ui::Overlay::Ring;
  s.view = ui::ViewTransform{Position(1.25, -3.5), 87.5};
  PinnedRow a{QStringLiteral("HPF, ε = 0.12"), settingsOf("hpf", "addition"), 0.1};
  a.settings.parameters.set("epsilon", 0.12);
  PinnedRow b{QStringLiteral("HIMM"), settingsOf("himm", "himm"), 0.05};
  b.settings.pose = PoseSource::Truth;
  s.pinnedRows = {a, b};
  s.sweep.model = "parameterized";
  s.sweep.rule = "bayes";
  s.sweep.pose = PoseSource::Truth;
  s.sweep.base = {{"no_echo", 1.0}};
  s.sweep.useSecondRun = false;
  return s;
}

QByteArray validText() {
  return QByteArrayLiteral(
      "{\n"
      "  \"format\": \"sonargrid-project\",\n"
      "  \"version\": 1,\n"
      "  \"log\": \"room.sglog\",\n"
      "  \"mapping\": {\"model\": \"hpf\", \"rule\": \"addition\", \"pose\": \"odom\",\n"
      "              \"cell\": 0.05, \"parameters\": {\"epsilon\": 0.1}}\n"
      "}\n");
}

}  // namespace

class TestProjectFile : public QObject {
  Q_OBJECT

 private slots:
  void roundTripsEveryField() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const ProjectState saved = everyFieldSet(dir.path());
    const QString file = dir.filePath(QStringLiteral("p.sgproj"));
    writeProject(saved, file);
    const ProjectState read = readProject(file);

    QCOMPARE(read.logPath, saved.logPath);
    QVERIFY(read.logReading == saved.logReading);
    QCOMPARE(read.logReading.ring->sonars.size(), std::size_t{24});
    QCOMPARE(read.logReading.posesPath, saved.logReading.posesPath);
    QCOMPARE(read.secondLogPath, saved.secondLogPath);
    QVERIFY(read.reference.has_value());
    QCOMPARE(referenceJsonText(*read.reference), referenceJsonText(*saved.reference));
    QCOMPARE(read.reference->unit, LengthUnit::Centimetre);
    QCOMPARE(read.referencePath, saved.referencePath);
    QCOMPARE(read.referenceModified, true);
    QCOMPARE(read.settings.model, saved.settings.model);
    QCOMPARE(read.settings.rule, saved.settings.rule);
    QCOMPARE(read.settings.pose, saved.settings.pose);
    QVERIFY(read.settings.parameters == saved.settings.parameters);
    QCOMPARE(read.settings.parameters.get("p2"), 0.15);
    QCOMPARE(read.cellSize, saved.cellSize);
    QCOMPARE(read.overlays, saved.overlays);
    QVERIFY(read.view.has_value());
    QCOMPARE(*read.view, *saved.view);
    QVERIFY(read.pinnedRows == saved.pinnedRows);
    QCOMPARE(read.pinnedRows.at(0).label, QStringLiteral("HPF, ε = 0.12"));
    QVERIFY(read.sweep == saved.sweep);

    // Saved again, the text is the same: nothing drifts through a round trip.
    QCOMPARE(projectJson(read, file), projectJson(saved, file));
  }

  void pathsAreRelativeToTheProject() {
    QTemporaryDir dir;
    ProjectState s;
    s.logPath = dir.filePath(QStringLiteral("logs/a.sglog"));
    const QString file = dir.filePath(QStringLiteral("p.sgproj"));
    const QByteArray text = projectJson(s, file);
    QVERIFY2(text.contains("\"log\": \"logs/a.sglog\""), text.constData());
    // A log read by its content alone: the project says nothing of how.
    QVERIFY2(!text.contains("log_reading"), text.constData());
    // The whole folder moved: the log is found beside the project's new place.
    const ProjectState moved = parseProject(text, QStringLiteral("/elsewhere/p.sgproj"));
    QCOMPARE(moved.logPath, QStringLiteral("/elsewhere/logs/a.sglog"));
    // An autosave names logs absolutely.
    QVERIFY(projectJson(s, file, ProjectPaths::Absolute).contains(s.logPath.toUtf8()));
  }

  void referenceByPathIsReadFromItsFile() {
    QTemporaryDir dir;
    ProjectState s;
    s.reference = readReferenceJson(kRoomReference.toStdString());
    s.referencePath = kRoomReference;
    s.referenceModified = false;
    const QString file = dir.filePath(QStringLiteral("p.sgproj"));
    const QByteArray text = projectJson(s, file);
    QVERIFY(!text.contains("\"inline\""));  // saved in its file: the project names it only
    const ProjectState read = parseProject(text, file);
    QVERIFY(read.reference.has_value());
    QCOMPARE(referenceJsonText(*read.reference), referenceJsonText(*s.reference));
    QCOMPARE(read.referenceModified, false);
  }

  void corruptProjectIsRefusedWithItsPlace_data() {
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("message");  // what the error must contain
    QByteArray text = validText();
    // A brace missing after line 3's value: the parser stops on line 4.
    QTest::newRow("syntax") << QByteArray(text).replace("\"version\": 1,", "\"version\": 1")
                            << QStringLiteral("p.sgproj:4: not valid JSON");
    QTest::newRow("empty") << QByteArray() << QStringLiteral("p.sgproj:1: not valid JSON");
    QTest::newRow("format") << QByteArray(text).replace("sonargrid-project", "something")
                            << QStringLiteral("p.sgproj: format: expected \"sonargrid-project\"");
    QTest::newRow("newer version") << QByteArray(text).replace("\"version\": 1", "\"version\": 9")
                                   << QStringLiteral("p.sgproj: version: version 9 is newer");
    QTest::newRow("no mapping") << QByteArray(text).replace("\"mapping\"", "\"mappin\"")
                                << QStringLiteral("p.sgproj: mapping: missing");
    // HPF's ε spans [0.005, 1] m (hpf.cpp): 7 is outside.
    QTest::newRow("parameter range")
        << QByteArray(text).replace("\"epsilon\": 0.1", "\"epsilon\": 7")
        << QStringLiteral("p.sgproj: mapping.parameters.epsilon:");
    QTest::newRow("unknown parameter")
        << QByteArray(text).replace("\"epsilon\": 0.1", "\"epsilonn\": 0.1")
        << QStringLiteral("p.sgproj: mapping.parameters.epsilonn:");
    QTest::newRow("cell") << QByteArray(text).replace("\"cell\": 0.05", "\"cell\": 2")
                          << QStringLiteral("p.sgproj: mapping.cell: 2 m is outside");
    QTest::newRow("pose") << QByteArray(text).replace("\"odom\"", "\"gps\"")
                          << QStringLiteral("p.sgproj: mapping.pose: expected");
    QTest::newRow("model") << QByteArray(text).replace("\"hpf\"", "\"nosuch\"")
                           << QStringLiteral("p.sgproj: mapping:");
    QTest::newRow("overlay") << QByteArray(text).replace(
                                    "\"log\":", "\"overlays\": [\"path\", \"clouds\"], \"log\":")
                             << QStringLiteral("p.sgproj: overlays[1]: unknown overlay \"clouds\"");
    QTest::newRow("view") << QByteArray(text).replace(
                                 "\"log\":",
                                 "\"view\": {\"centre\": [1], \"pixels_per_metre\": 5}, \"log\":")
                          << QStringLiteral("p.sgproj: view.centre: expected [x, y]");
    QTest::newRow("pinned row") << QByteArray(text).replace(
                                       "\"log\":", "\"pinned\": [{\"model\": \"hpf\"}], \"log\":")
                                << QStringLiteral("p.sgproj: pinned[0].rule: missing");
    QTest::newRow("log format") << QByteArray(text).replace(
                                       "\"log\":",
                                       "\"log_reading\": {\"format\": \"rosbag\"}, \"log\":")
                                << QStringLiteral(
                                       "p.sgproj: log_reading.format: unknown log format");
    QTest::newRow("log columns")
        << QByteArray(text).replace("\"log\":",
                                    "\"log_reading\": {\"columns\": \"time=1,sonars=0\"}, \"log\":")
        << QStringLiteral("p.sgproj: log_reading.columns: --columns item 'sonars=0'");
    QTest::newRow("log ring")
        << QByteArray(text).replace(
               "\"log\":",
               "\"log_reading\": {\"ring\": {\"aperture\": 0.4, \"min_range\": "
               "0.1, \"max_range\": 5, \"sonars\": [[0, 0]]}}, \"log\":")
        << QStringLiteral("p.sgproj: log_reading.ring.sonars[0]: expected");
    QTest::newRow("log topics") << QByteArray(text).replace(
                                       "\"log\":",
                                       "\"log_reading\": {\"topics\": {\"sonar\": [3]}}, \"log\":")
                                << QStringLiteral(
                                       "p.sgproj: log_reading.topics.sonar[0]: expected a topic");
    QTest::newRow("start pose") << QByteArray(text).replace(
                                       "\"log\":",
                                       "\"log_reading\": {\"start_pose\": [1, 2]}, \"log\":")
                                << QStringLiteral(
                                       "p.sgproj: log_reading.start_pose: expected [x, y, theta]");
    QTest::newRow("inline reference")
        << QByteArray(text).replace(
               "\"log\":",
               "\"reference\": {\"inline\": {\"format\": \"sonargrid-reference\", \"version\": 1, "
               "\"units\": \"m\", \"objects\": [{\"name\": \"a\", \"closed\": true, \"corners\": "
               "[[0, 0], [1, 0]]}]}}, \"log\":")
        << QStringLiteral("p.sgproj: reference:");
  }

  // A bag's topics and a CSV log's columns as the file holds them (docs/formats.md, "Project
  // file"): what reopens the log as it was read.
  void logReadingReadsBack() {
    const QByteArray text =
        QByteArray(validText())
            .replace("\"log\":",
                     "\"log_reading\": {\"format\": \"bag\", \"topics\": {\"sonar\": "
                     "[\"/RosAria/sonar\"], "
                     "\"odometry\": \"/RosAria/pose\", \"truth\": \"-\"}, \"ring\": {\"robot\": "
                     "\"p3dx\", "
                     "\"aperture\": 0.4363323129985824, \"min_range\": 0.15, \"max_range\": 5, "
                     "\"sonars\": "
                     "[[0.069, 0.136, 1.5707963267948966], [0.114, 0.119, 0.8726646259971648]]}, "
                     "\"poses\": \"p.csv\", \"start_pose\": [1.5, -2, 3.0]}, \"log\":");
    const ProjectState s = parseProject(text, QStringLiteral("/data/p.sgproj"));
    QVERIFY(s.logReading.startPose == Pose2D(1.5, -2.0, 3.0));
    QCOMPARE(s.logReading.format, LogFormat::Bag);
    QCOMPARE(s.logReading.topics.sonar, std::vector<std::string>{"/RosAria/sonar"});
    QCOMPARE(s.logReading.topics.odometry, std::string("/RosAria/pose"));
    QCOMPARE(s.logReading.topics.truth, std::string("-"));
    QVERIFY(s.logReading.ring.has_value());
    QCOMPARE(s.logReading.ring->robot, std::string("p3dx"));
    QCOMPARE(s.logReading.ring->sonars.size(), std::size_t{2});
    QCOMPARE(s.logReading.ring->sonars[1].pose.heading, 0.8726646259971648);  // 50 degrees
    QCOMPARE(s.logReading.ring->maxRange, 5.0);
    QCOMPARE(s.logReading.posesPath, QStringLiteral("/data/p.csv"));
    const LogOptions o = optionsOf(s.logReading);
    QCOMPARE(o.format, LogFormat::Bag);
    QVERIFY(o.topics == s.logReading.topics);
    QVERIFY(readingOf(o) == s.logReading);
  }

  void corruptProjectIsRefusedWithItsPlace() {
    QFETCH(QByteArray, text);
    QFETCH(QString, message);
    try {
      parseProject(text, QStringLiteral("p.sgproj"));
      QFAIL("the corrupt project was accepted");
    } catch (const ProjectError& e) {
      QVERIFY2(QString::fromUtf8(e.what()).contains(message), e.what());
    }
  }

  void unwritableFolderIsAnError() {
    const QString file = QStringLiteral("/nonexistent-folder-sonargrid/p.sgproj");
    try {
      writeProject(ProjectState{}, file);
      QFAIL("wrote into a folder that does not exist");
    } catch (const ProjectError& e) {
      QVERIFY2(QString::fromUtf8(e.what()).contains(file), e.what());
    }
    try {
      readProject(file);
      QFAIL("read a file that does not exist");
    } catch (const ProjectError& e) {
      QVERIFY2(QString::fromUtf8(e.what()).contains(file), e.what());
    }
  }
};

QTEST_MAIN(TestProjectFile)
#include "tst_project_file.moc"
