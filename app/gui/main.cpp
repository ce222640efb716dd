// SPDX-License-Identifier: GPL-3.0-or-later
// sonargrid: the desktop app. Only the command line lives here; the window is main_window.cpp.
//
//   sonargrid [LOG] [--reference REF] [--model M --rule R --set k=v ...] [--pose odom|truth]
//             [--cell METRES] [--raster] [--inspect X,Y] [--screenshot FILE] [--metrics-json FILE]
//   sonargrid PROJECT.sgproj [--raster] [--inspect X,Y] [--screenshot FILE] [--metrics-json FILE]

#include <QApplication>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QPixmap>
#include <QScreen>
#include <QTimer>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string_view>

#include "cell_inspector.h"
#include "comparison_table.h"
#include "document.h"
#include "export_file.h"
#include "main_window.h"
#include "metrics_panel.h"
#include "preferences.h"
#include "project_file.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/forward/forward_em.h"

namespace {

struct UsageError {
  QString message;
};

QString joined(const std::vector<std::string>& names) {
  QStringList out;
  for (const std::string& n : names) out << QString::fromStdString(n);
  return out.join(QStringLiteral(", "));
}

// Model, rule, pose and --set values on top of what the user chose last time.
sg::MapperSettings settingsFrom(const QCommandLineParser& args) {
  sg::MapperSettings s = sg::app::MainWindow::lastSettings();
  const bool newPair = args.isSet("model") || args.isSet("rule");
  if (args.isSet("model")) s.model = args.value("model").toStdString();
  if (args.isSet("rule")) s.rule = args.value("rule").toStdString();
  // The forward model's rule is EM itself: --model forward-em alone names the pair.
  if (args.isSet("model") && !args.isSet("rule") && sg::forward::isForwardModel(s.model))
    s.rule = sg::forward::kRuleName;
  const std::vector<std::string> models = sg::forward::mapModelNames();
  const std::vector<std::string> rules = sg::forward::mapRuleNames();
  if (std::find(models.begin(), models.end(), s.model) == models.end())
    throw UsageError{QStringLiteral("unknown --model '%1'; choose one of %2")
                         .arg(QString::fromStdString(s.model), joined(models))};
  if (std::find(rules.begin(), rules.end(), s.rule) == rules.end())
    throw UsageError{QStringLiteral("unknown --rule '%1'; choose one of %2")
                         .arg(QString::fromStdString(s.rule), joined(rules))};
  const sg::Compatibility c = sg::forward::mapCompatibility(s.model, s.rule);
  if (!c.allowed)
    throw UsageError{QStringLiteral("model '%1' cannot be used with rule '%2': %3")
                         .arg(QString::fromStdString(s.model), QString::fromStdString(s.rule),
                              QString::fromStdString(c.reason))};
  if (newPair) s.parameters = sg::forward::mapDefaultParameters(s.model, s.rule);
  QStringList seen;
  for (const QString& kv : args.values("set")) {
    const qsizetype eq = kv.indexOf('=');
    if (eq <= 0) throw UsageError{QStringLiteral("--set expects NAME=VALUE, got '%1'").arg(kv)};
    const QString name = kv.left(eq);
    if (seen.contains(name)) throw UsageError{QStringLiteral("--set %1 is given twice").arg(name)};
    seen << name;
    bool ok = false;
    const double value = kv.mid(eq + 1).toDouble(&ok);
    if (!ok || !std::isfinite(value))
      throw UsageError{QStringLiteral("--set %1: '%2' is not a number").arg(name, kv.mid(eq + 1))};
    try {
      s.parameters.set(name.toStdString(), value);
    } catch (const sg::ParameterError& e) {
      throw UsageError{QStringLiteral("--set: %1").arg(QString::fromUtf8(e.what()))};
    }
  }
  if (args.isSet("pose")) {
    const QString pose = args.value("pose");
    if (pose == QLatin1String("truth"))
      s.pose = sg::PoseSource::Truth;
    else if (pose == QLatin1String("odom"))
      s.pose = sg::PoseSource::Odometry;
    else
      throw UsageError{QStringLiteral("--pose takes odom or truth, got '%1'").arg(pose)};
  }
  return s;
}

// --inspect: traces the cell at `world` and shows its last reading (the timeline moves to it).
// False, after saying why, when the point is off the grid or the trace fails.
bool inspectCell(sg::app::MainWindow& window, const sg::Position& world) {
  sg::ui::CellInspector* inspector = window.cellInspector();
  if (!inspector->inspectAt(world)) {
    std::cerr << "sonargrid: --inspect " << world.x() << "," << world.y()
              << " is outside the grid\n";
    return false;
  }
  if (auto* dock = window.findChild<QDockWidget*>(QStringLiteral("cellInspectorDock"))) {
    dock->show();
    dock->raise();
  }
  QElapsedTimer clock;
  clock.start();
  while (inspector->busy() && clock.elapsed() < 120000)
    QApplication::processEvents(QEventLoop::AllEvents, 50);
  if (!inspector->trace()) {
    std::cerr << "sonargrid: the cell inspector did not trace the cell\n";
    return false;
  }
  if (!inspector->trace()->steps.empty())
    inspector->selectStep(inspector->trace()->steps.size() - 1);
  return true;
}

// The command line, the same for the window and for --help / --version.
void describeOptions(QCommandLineParser& parser) {
  parser.setApplicationDescription(
      QStringLiteral("SonarGrid: build and compare sonar occupancy grids."));
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument(QStringLiteral("LOG"),
                               QStringLiteral("A log (.sglog, CARMEN, Player, CSV) or a project "
                                              "(.sgproj) to open. A log of a bundled dataset "
                                              "opens with the dataset's reference map."),
                               QStringLiteral("[LOG | PROJECT.sgproj]"));
  parser.addOptions({
      {QStringLiteral("reference"), QStringLiteral("Reference map (.json, .map, .yaml)."),
       QStringLiteral("REF")},
      {QStringLiteral("model"), QStringLiteral("Sensor model (see sonargrid-cli models)."),
       QStringLiteral("M")},
      {QStringLiteral("rule"), QStringLiteral("Update rule."), QStringLiteral("R")},
      {QStringLiteral("set"), QStringLiteral("A parameter value; repeat for several."),
       QStringLiteral("NAME=VALUE")},
      {QStringLiteral("pose"), QStringLiteral("Pose to map with: odom or truth."),
       QStringLiteral("SOURCE")},
      {QStringLiteral("cell"), QStringLiteral("Cell size in metres (default 0.05)."),
       QStringLiteral("METRES")},
      {QStringLiteral("raster"), QStringLiteral("Draw the grid without OpenGL.")},
      {QStringLiteral("inspect"),
       QStringLiteral("Inspect the cell at world point X,Y (metres) once mapped: the Cell "
                      "Inspector traces it and shows its last reading in the beam view."),
       QStringLiteral("X,Y")},
      {QStringLiteral("screenshot"),
       QStringLiteral("Load, map, save a picture of the window to FILE and exit."),
       QStringLiteral("FILE")},
      {QStringLiteral("metrics-json"),
       QStringLiteral("Load, map, write the metrics panel's numbers (the keys of sonargrid-cli "
                      "score --json) to FILE and exit."),
       QStringLiteral("FILE")},
  });
}

void nameApplication() {
  QCoreApplication::setOrganizationName(QStringLiteral("SonarGrid"));
  QCoreApplication::setApplicationName(QStringLiteral("sonargrid"));
  QCoreApplication::setApplicationVersion(QStringLiteral(SONARGRID_VERSION));
}

// --help, --help-all, --version (and -h, -?, -v) need no window: they are answered before the
// QApplication exists, so they print and exit 0 without a display.
bool asksForTextOnly(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--") break;
    if (a == "-h" || a == "-?" || a == "--help" || a == "--help-all" || a == "-v" ||
        a == "--version")
      return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (asksForTextOnly(argc, argv)) {
    QCoreApplication text(argc, argv);
    nameApplication();
    QCommandLineParser parser;
    describeOptions(parser);
    parser.process(text);  // prints and exits 0
    return 0;
  }
  QApplication app(argc, argv);
  nameApplication();
  QApplication::setApplicationDisplayName(QStringLiteral("SonarGrid"));
  QApplication::setDesktopFileName(QStringLiteral("sonargrid"));

  QCommandLineParser parser;
  describeOptions(parser);
  parser.process(app);

  // The Mapping threads preference; a bad SONARGRID_THREADS is said once here (the core passes it
  // over), and the Preferences dialog says it again.
  try {
    sg::environmentThreadCount();
  } catch (const sg::ThreadCountError& e) {
    std::cerr << "sonargrid: " << e.what() << "; using the CPUs this process may use\n";
  }
  sg::app::applyMappingThreads();

  const QString file =
      parser.positionalArguments().isEmpty() ? QString() : parser.positionalArguments().front();
  const bool isProject = QFileInfo(file).suffix().compare(QLatin1String(sg::app::kProjectSuffix),
                                                          Qt::CaseInsensitive) == 0;
  sg::MapperSettings settings;
  double cell = sg::app::MainWindow::lastCellSize();
  std::optional<sg::Position> inspectAt;
  try {
    if (parser.positionalArguments().size() > 1)
      throw UsageError{QStringLiteral("give at most one LOG")};
    settings = settingsFrom(parser);
    if (parser.isSet("cell")) {
      bool ok = false;
      cell = parser.value("cell").toDouble(&ok);
      if (!ok || !(cell >= 0.005 && cell <= 1.0))
        throw UsageError{QStringLiteral("--cell takes metres in [0.005, 1], got '%1'")
                             .arg(parser.value("cell"))};
    }
    if (parser.isSet("inspect")) {
      const QStringList xy = parser.value("inspect").split(QLatin1Char(','));
      bool okX = false, okY = false;
      if (xy.size() == 2) inspectAt = sg::Position(xy[0].toDouble(&okX), xy[1].toDouble(&okY));
      if (!okX || !okY || !inspectAt->allFinite())
        throw UsageError{
            QStringLiteral("--inspect takes X,Y in metres, got '%1'").arg(parser.value("inspect"))};
    }
    for (const char* option : {"screenshot", "metrics-json"})
      if (parser.isSet(QString::fromLatin1(option)) && parser.positionalArguments().isEmpty())
        throw UsageError{QStringLiteral("--%1 needs a LOG or a PROJECT to map")
                             .arg(QString::fromLatin1(option))};
    if (isProject)
      for (const char* option : {"reference", "model", "rule", "set", "pose", "cell"})
        if (parser.isSet(QString::fromLatin1(option)))
          throw UsageError{QStringLiteral("--%1 cannot be given with a project: the project "
                                          "holds it (change it in the window and save)")
                               .arg(QString::fromLatin1(option))};
  } catch (const UsageError& e) {
    std::cerr << "sonargrid: " << e.message.toStdString() << '\n';
    return 2;
  }

  // Either writes its files and exits without waiting for the user (and without a display).
  const bool screenshot = parser.isSet("screenshot") || parser.isSet("metrics-json");
  sg::app::MainWindow window(parser.isSet("raster") ? sg::ui::GridView::Backend::Raster
                                                    : sg::ui::GridView::Backend::Automatic);
  if (screenshot) window.resize(1280, 800);
  // Settings on the command line are edits of the document that starts from the last session's
  // choices (so a --set that changes something leaves unsaved changes, autosaved as any edit).
  window.setCellSize(cell);
  // The rule changes only when --rule names it: the panel notes no rule change.
  window.setMapperSettings(settings, /*ruleNamed=*/true);
  // A reference given with a log is drawn for that log: the new log does not close it.
  if (parser.isSet("reference") && !window.openReference(parser.value("reference"), screenshot))
    if (screenshot) return 2;
  if (isProject) {
    if (!window.openProject(file, screenshot) && screenshot) return 2;
  } else if (!file.isEmpty() && !window.openLog(file, screenshot)) {
    if (screenshot) return 2;
  }
  window.show();
  // Test-only (docs/user-guide.md, "Projects"): SONARGRID_TEST_EDITS=FILE.sgproj makes that
  // project's reference map, settings and pinned rows three edits of the opened document, as the
  // user would make them, so that a test can kill a session with unsaved work.
  if (const QString edits = qEnvironmentVariable("SONARGRID_TEST_EDITS"); !edits.isEmpty()) {
    window.waitForLoad();
    try {
      const sg::app::ProjectState state = sg::app::readProject(edits);
      sg::app::Document& document = *window.document();
      document.setReference(state.reference, state.referencePath);
      document.setMapperSettings(state.settings);
      document.setPinnedRows(state.pinnedRows);
    } catch (const std::exception& e) {
      std::cerr << "sonargrid: SONARGRID_TEST_EDITS: " << e.what() << '\n';
      return 2;
    }
  }
  // A crashed session's autosave: offered when the user opened nothing else (SONARGRID_RECOVER
  // answers without a dialog; without a display nothing blocks).
  if (!screenshot && file.isEmpty()) window.offerRecovery();
  if (inspectAt && !file.isEmpty() && window.waitForMap(120000) &&
      !inspectCell(window, *inspectAt) && screenshot)
    return 1;

  if (screenshot) {
    if (!window.waitForMap(120000)) {  // again: an inspected reading maps up to its time
      std::cerr << "sonargrid: mapping did not finish\n";
      return 1;
    }
    if (parser.isSet("metrics-json")) {
      // The panel's numbers of the map the window shows, as `sonargrid-cli score --json` (and
      // `goodness --json` without a reference) writes them; the panel is brought to the front so
      // that the screenshot shows them.
      auto* panel = window.findChild<sg::ui::MetricsPanel*>();
      if (auto* dock = window.findChild<QDockWidget*>(QStringLiteral("metricsDock"))) dock->raise();
      if (!panel || !panel->waitForResult(300000) || !panel->result()) {
        std::cerr << "sonargrid: the metrics did not finish\n";
        return 1;
      }
      const QString jsonFile = parser.value("metrics-json");
      const std::string json = sg::ui::metricsJson(*panel->result()) + '\n';
      const QString error =
          sg::app::writeFileBytes(jsonFile, QByteArray(json.data(), qsizetype(json.size())));
      if (!error.isEmpty()) {
        std::cerr << "sonargrid: " << error.toStdString() << '\n';
        return 1;
      }
      std::cout << "wrote " << jsonFile.toStdString() << '\n';
      if (!parser.isSet("screenshot")) return 0;
      // A project's pinned rows: the comparison table shows them, computed.
      auto* table = window.findChild<sg::ui::ComparisonTable*>();
      if (table && !table->rows().empty()) {
        if (auto* dock = window.findChild<QDockWidget*>(QStringLiteral("comparisonDock")))
          dock->raise();
        table->waitForResult(300000);
      }
    }
    // Let the window lay out and paint the new map once before grabbing it.
    for (int i = 0; i < 5; ++i) QApplication::processEvents(QEventLoop::AllEvents, 20);
    const QString shotFile = parser.value("screenshot");
    // On a real display, take the pixels the X server shows (what the user sees, the OpenGL
    // surface included); elsewhere let the widgets render themselves.
    const bool onScreen = QGuiApplication::platformName() == QLatin1String("xcb");
    const QPixmap shot = onScreen ? window.screen()->grabWindow(window.winId()) : window.grab();
    // The format follows the name's suffix, as QPixmap::save(file) would choose it.
    const QString suffix = QFileInfo(shotFile).suffix();
    const QByteArray format = suffix.isEmpty() ? QByteArray("PNG") : suffix.toLatin1();
    const QByteArray bytes = sg::app::encodedImage(shot.toImage(), format.constData());
    const QString error =
        bytes.isEmpty() ? shotFile + QStringLiteral(": cannot encode the screenshot as ") + format
                        : sg::app::writeFileBytes(shotFile, bytes);
    if (!error.isEmpty()) {
      std::cerr << "sonargrid: " << error.toStdString() << '\n';
      return 1;
    }
    std::cout << "wrote " << shotFile.toStdString() << '\n';
    return 0;
  }
  return app.exec();
}
