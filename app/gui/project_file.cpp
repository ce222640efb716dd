// SPDX-License-Identifier: GPL-3.0-or-later
#include "project_file.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <cmath>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/io/csv_layout.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sonargrid/sweep/sweep_metrics.h"

namespace sg::app {
namespace {

struct OverlayName {
  ui::Overlay overlay;
  const char* name;
};
constexpr OverlayName kOverlayNames[] = {{ui::Overlay::Reference, "reference"},
                                         {ui::Overlay::Path, "path"},
                                         {ui::Overlay::Robot, "robot"},
                                         {ui::Overlay::Beams, "beams"},
                                         {ui::Overlay::Ring, "ring"},
                                         {ui::Overlay::Legend, "legend"},
                                         {ui::Overlay::Dmin, "dmin"}};

QString poseText(PoseSource p) {
  return p == PoseSource::Truth ? QStringLiteral("truth") : QStringLiteral("odom");
}

QString storedPath(const QString& path, const QString& projectPath, ProjectPaths paths) {
  if (path.isEmpty()) return path;
  const QString absolute = QFileInfo(path).absoluteFilePath();
  if (paths == ProjectPaths::Absolute) return absolute;
  return QFileInfo(projectPath).absoluteDir().relativeFilePath(absolute);
}

QJsonObject parametersJson(const ParameterSet& p) {
  QJsonObject o;
  for (const auto& [name, value] : p.values()) o.insert(QString::fromStdString(name), value);
  return o;
}

QJsonObject settingsJson(const MapperSettings& s, double cell) {
  return QJsonObject{{"model", QString::fromStdString(s.model)},
                     {"rule", QString::fromStdString(s.rule)},
                     {"pose", poseText(s.pose)},
                     {"cell", cell},
                     {"parameters", parametersJson(s.parameters)}};
}

QString resolved(const QString& stored, const QString& projectPath) {
  if (stored.isEmpty()) return stored;
  return QFileInfo(QFileInfo(projectPath).absoluteDir(), stored).absoluteFilePath();
}

QJsonObject ringJson(const SonarRing& ring) {
  QJsonArray sonars;
  for (const SonarMount& m : ring.sonars)
    sonars.append(QJsonArray{m.pose.x(), m.pose.y(), m.pose.heading});
  return QJsonObject{{"robot", QString::fromStdString(ring.robot)},
                     {"aperture", ring.apertureRad},
                     {"min_range", ring.minRange},
                     {"max_range", ring.maxRange},
                     {"sonars", sonars}};
}

// Only what differs from reading the file by its content alone.
QJsonObject readingJson(const LogReading& r, const QString& projectPath, ProjectPaths paths) {
  QJsonObject o;
  if (r.format != LogFormat::Auto)
    o.insert("format", QString::fromLatin1(logFormatName(r.format).data(),
                                           static_cast<qsizetype>(logFormatName(r.format).size())));
  if (r.lenient) o.insert("lenient", true);
  if (r.ring) o.insert("ring", ringJson(*r.ring));
  if (r.csv) o.insert("columns", QString::fromStdString(formatCsvLayout(*r.csv)));
  if (!r.posesPath.isEmpty()) o.insert("poses", storedPath(r.posesPath, projectPath, paths));
  if (!r.topics.empty()) {
    QJsonArray sonar;
    for (const std::string& t : r.topics.sonar) sonar.append(QString::fromStdString(t));
    o.insert("topics", QJsonObject{{"sonar", sonar},
                                   {"odometry", QString::fromStdString(r.topics.odometry)},
                                   {"truth", QString::fromStdString(r.topics.truth)}});
  }
  if (r.startPose)
    o.insert("start_pose", QJsonArray{r.startPose->x(), r.startPose->y(), r.startPose->heading});
  return o;
}

// Reading: every accessor names the field it reads, so an error says where it is.
class Reader {
 public:
  explicit Reader(QString file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const QString& field, const QString& message) const {
    throw ProjectError(
        (file_ + QStringLiteral(": ") + field + QStringLiteral(": ") + message).toStdString());
  }

  QJsonValue member(const QJsonObject& o, const QString& field, const QString& key,
                    bool required) const {
    const QJsonValue v = o.value(key);
    if (v.isUndefined() && required) fail(join(field, key), QStringLiteral("missing"));
    return v;
  }
  QString string(const QJsonObject& o, const QString& field, const QString& key, bool required,
                 const QString& fallback = {}) const {
    const QJsonValue v = member(o, field, key, required);
    if (v.isUndefined() || v.isNull()) return fallback;
    if (!v.isString()) fail(join(field, key), QStringLiteral("expected a string"));
    return v.toString();
  }
  double number(const QJsonObject& o, const QString& field, const QString& key) const {
    const QJsonValue v = member(o, field, key, true);
    if (!v.isDouble() || !std::isfinite(v.toDouble()))
      fail(join(field, key), QStringLiteral("expected a number"));
    return v.toDouble();
  }
  QJsonObject object(const QJsonObject& o, const QString& field, const QString& key,
                     bool required) const {
    const QJsonValue v = member(o, field, key, required);
    if (v.isUndefined() || v.isNull()) return {};
    if (!v.isObject()) fail(join(field, key), QStringLiteral("expected an object"));
    return v.toObject();
  }
  QJsonArray array(const QJsonObject& o, const QString& field, const QString& key) const {
    const QJsonValue v = member(o, field, key, false);
    if (v.isUndefined() || v.isNull()) return {};
    if (!v.isArray()) fail(join(field, key), QStringLiteral("expected an array"));
    return v.toArray();
  }
  static QString join(const QString& field, const QString& key) {
    return field.isEmpty() ? key : field + QLatin1Char('.') + key;
  }

  PoseSource pose(const QJsonObject& o, const QString& field) const {
    const QString p = string(o, field, QStringLiteral("pose"), false, QStringLiteral("odom"));
    if (p == QLatin1String("truth")) return PoseSource::Truth;
    if (p == QLatin1String("odom")) return PoseSource::Odometry;
    fail(join(field, QStringLiteral("pose")),
         QStringLiteral("expected \"odom\" or \"truth\", got \"%1\"").arg(p));
  }

  double cell(const QJsonObject& o, const QString& field) const {
    const double c = number(o, field, QStringLiteral("cell"));
    if (!(c >= kMinCellSize && c <= kMaxCellSize))
      fail(join(field, QStringLiteral("cell")),
           QStringLiteral("%1 m is outside [%2, %3] m").arg(c).arg(kMinCellSize).arg(kMaxCellSize));
    return c;
  }

  bool boolean(const QJsonObject& o, const QString& field, const QString& key) const {
    const QJsonValue v = member(o, field, key, false);
    if (v.isUndefined()) return false;
    if (!v.isBool()) fail(join(field, key), QStringLiteral("expected true or false"));
    return v.toBool();
  }

  SonarRing ring(const QJsonObject& o, const QString& field) const {
    SonarRing ring;
    ring.robot =
        string(o, field, QStringLiteral("robot"), false, QStringLiteral("custom")).toStdString();
    ring.apertureRad = number(o, field, QStringLiteral("aperture"));
    ring.minRange = number(o, field, QStringLiteral("min_range"));
    ring.maxRange = number(o, field, QStringLiteral("max_range"));
    if (!(ring.apertureRad > 0.0) || !(ring.minRange >= 0.0) || !(ring.maxRange > ring.minRange))
      fail(field, QStringLiteral("expected aperture > 0 and 0 <= min_range < max_range"));
    const QJsonArray sonars = array(o, field, QStringLiteral("sonars"));
    if (sonars.isEmpty()) fail(join(field, QStringLiteral("sonars")), QStringLiteral("empty"));
    for (qsizetype i = 0; i < sonars.size(); ++i) {
      const QJsonArray p = sonars[i].toArray();
      bool ok = sonars[i].isArray() && p.size() == 3;
      for (qsizetype k = 0; ok && k < 3; ++k)
        ok = p[k].isDouble() && std::isfinite(p[k].toDouble());
      if (!ok)
        fail(QStringLiteral("%1.sonars[%2]").arg(field).arg(i),
             QStringLiteral("expected [x, y, theta] in metres and radians"));
      ring.sonars.push_back(SonarMount{Pose2D(p[0].toDouble(), p[1].toDouble(), p[2].toDouble())});
    }
    return ring;
  }

  LogReading reading(const QJsonObject& o, const QString& field, const QString& projectPath) const {
    LogReading r;
    const QString format =
        string(o, field, QStringLiteral("format"), false, QStringLiteral("auto"));
    if (!parseLogFormat(format.toStdString(), r.format))
      fail(join(field, QStringLiteral("format")),
           QStringLiteral("unknown log format \"%1\"").arg(format));
    r.lenient = boolean(o, field, QStringLiteral("lenient"));
    const QJsonObject ringObject = object(o, field, QStringLiteral("ring"), false);
    if (!ringObject.isEmpty()) r.ring = ring(ringObject, join(field, QStringLiteral("ring")));
    const QString columns = string(o, field, QStringLiteral("columns"), false);
    if (!columns.isEmpty()) {
      try {
        r.csv = parseCsvLayout(columns.toStdString());
      } catch (const std::invalid_argument& e) {
        fail(join(field, QStringLiteral("columns")), QString::fromUtf8(e.what()));
      }
    }
    r.posesPath = resolved(string(o, field, QStringLiteral("poses"), false), projectPath);
    const QJsonObject topics = object(o, field, QStringLiteral("topics"), false);
    if (!topics.isEmpty()) {
      const QString tf = join(field, QStringLiteral("topics"));
      const QJsonArray sonar = array(topics, tf, QStringLiteral("sonar"));
      for (qsizetype i = 0; i < sonar.size(); ++i) {
        if (!sonar[i].isString() || sonar[i].toString().isEmpty())
          fail(QStringLiteral("%1.sonar[%2]").arg(tf).arg(i), QStringLiteral("expected a topic"));
        r.topics.sonar.push_back(sonar[i].toString().toStdString());
      }
      r.topics.odometry = string(topics, tf, QStringLiteral("odometry"), false).toStdString();
      r.topics.truth = string(topics, tf, QStringLiteral("truth"), false).toStdString();
    }
    if (o.contains(QStringLiteral("start_pose"))) {
      const QJsonArray p = array(o, field, QStringLiteral("start_pose"));
      bool ok = p.size() == 3;
      for (qsizetype k = 0; ok && k < 3; ++k)
        ok = p[k].isDouble() && std::isfinite(p[k].toDouble());
      if (!ok)
        fail(join(field, QStringLiteral("start_pose")),
             QStringLiteral("expected [x, y, theta] in metres and radians"));
      r.startPose = Pose2D(p[0].toDouble(), p[1].toDouble(), p[2].toDouble());
    }
    return r;
  }

  MapperSettings settings(const QJsonObject& o, const QString& field) const {
    MapperSettings s;
    s.model = string(o, field, QStringLiteral("model"), true).toStdString();
    s.rule = string(o, field, QStringLiteral("rule"), true).toStdString();
    const Compatibility c = forward::mapCompatibility(s.model, s.rule);
    if (c.allowed) {
      try {
        s.parameters = forward::mapDefaultParameters(s.model, s.rule);
      } catch (const std::exception& e) {
        fail(field, QString::fromUtf8(e.what()));
      }
    }
    if (!c.allowed) fail(join(field, QStringLiteral("rule")), QString::fromStdString(c.reason));
    s.pose = pose(o, field);
    const QString pfield = join(field, QStringLiteral("parameters"));
    const QJsonObject params = object(o, field, QStringLiteral("parameters"), false);
    for (auto it = params.begin(); it != params.end(); ++it) {
      const QString name = join(pfield, it.key());
      if (!it.value().isDouble()) fail(name, QStringLiteral("expected a number"));
      try {
        s.parameters.set(it.key().toStdString(), it.value().toDouble());
      } catch (const ParameterError& e) {
        fail(name, QString::fromUtf8(e.what()));
      }
    }
    return s;
  }

 private:
  QString file_;
};

}  // namespace

QByteArray projectJson(const ProjectState& state, const QString& projectPath, ProjectPaths paths) {
  QJsonObject root{{"format", kProjectFormat}, {"version", kProjectVersion}};
  root.insert("log", storedPath(state.logPath, projectPath, paths));
  if (state.logReading != LogReading{})
    root.insert("log_reading", readingJson(state.logReading, projectPath, paths));
  root.insert("second_log", storedPath(state.secondLogPath, projectPath, paths));
  if (state.reference) {
    QJsonObject ref{{"path", storedPath(state.referencePath, projectPath, paths)}};
    if (state.referenceModified || state.referencePath.isEmpty()) {
      try {
        const std::string text = referenceJsonText(*state.reference);
        ref.insert("inline", QJsonDocument::fromJson(QByteArray::fromStdString(text)).object());
      } catch (const std::invalid_argument&) {
        // A raster reference (ROS map) has no JSON form: its path is all the project can hold.
      }
    }
    root.insert("reference", ref);
  } else {
    root.insert("reference", QJsonValue::Null);
  }
  root.insert("mapping", settingsJson(state.settings, state.cellSize));
  QJsonArray overlays;
  for (const OverlayName& o : kOverlayNames)
    if (state.overlays.testFlag(o.overlay)) overlays.append(QString::fromLatin1(o.name));
  root.insert("overlays", overlays);
  if (state.view)
    root.insert("view",
                QJsonObject{{"centre", QJsonArray{state.view->centre.x(), state.view->centre.y()}},
                            {"pixels_per_metre", state.view->pixelsPerMetre}});
  else
    root.insert("view", QJsonValue::Null);
  QJsonArray pinned;
  for (const PinnedRow& row : state.pinnedRows) {
    QJsonObject o = settingsJson(row.settings, row.cellSize);
    o.insert("label", row.label);
    pinned.append(o);
  }
  root.insert("pinned", pinned);
  // Only what applies to the sweep's model and rule: the sweep form keeps, say, paper 002's axes
  // while HIMM is chosen, and a project holding them would not reopen.
  SweepPlan plan = state.sweep;
  (void)keepApplicable(plan);
  QJsonObject base;
  for (const auto& [name, value] : plan.base) base.insert(QString::fromStdString(name), value);
  auto texts = [](const std::vector<std::string>& list) {
    QJsonArray a;
    for (const std::string& t : list) a.append(QString::fromStdString(t));
    return a;
  };
  root.insert("sweep", QJsonObject{{"model", QString::fromStdString(plan.model)},
                                   {"rule", QString::fromStdString(plan.rule)},
                                   {"pose", poseText(plan.pose)},
                                   {"grid", QString::fromStdString(plan.parameterGrid)},
                                   {"axes", texts(plan.axes)},
                                   {"ties", texts(plan.ties)},
                                   {"metrics", texts(plan.metrics)},
                                   {"base", base},
                                   {"use_second_run", plan.useSecondRun}});
  return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

QStringList keepApplicable(SweepPlan& plan) {
  QStringList dropped;
  ParameterSet declared;
  try {
    declared = defaultParameters(plan.model, plan.rule);
  } catch (const std::exception&) {
    return dropped;  // an unknown model or rule: parseProject() refuses the file
  }
  auto keep = [&](const char* key, std::vector<std::string>& list, auto check) {
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < list.size(); ++i) {
      try {
        check(list[i]);
        kept.push_back(list[i]);
      } catch (const std::exception& e) {
        dropped << QStringLiteral("sweep.%1[%2] '%3': %4")
                       .arg(QLatin1String(key))
                       .arg(i)
                       .arg(QString::fromStdString(list[i]), QString::fromUtf8(e.what()));
      }
    }
    list = std::move(kept);
  };
  keep("axes", plan.axes, [&](const std::string& t) { (void)parseSweepAxis(t, declared); });
  keep("ties", plan.ties, [&](const std::string& t) { (void)parseSweepTie(t, declared); });
  keep("metrics", plan.metrics, [](const std::string& t) { (void)parseSweepMetrics({t}); });
  for (auto it = plan.base.begin(); it != plan.base.end();) {
    try {
      ParameterSet probe = declared;
      probe.set(it->first, it->second);  // names an undeclared parameter or the range missed
      ++it;
    } catch (const ParameterError& e) {
      dropped << QStringLiteral("sweep.base.%1: %2")
                     .arg(QString::fromStdString(it->first), QString::fromUtf8(e.what()));
      it = plan.base.erase(it);
    }
  }
  return dropped;
}

ProjectState parseProject(const QByteArray& text, const QString& projectPath,
                          QStringList* dropped) {
  const QString file = QDir::toNativeSeparators(projectPath);
  const Reader r(file);
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(text, &error);
  if (error.error != QJsonParseError::NoError) {
    const int line = static_cast<int>(text.left(error.offset).count('\n')) + 1;
    throw ProjectError(QStringLiteral("%1:%2: not valid JSON: %3")
                           .arg(file)
                           .arg(line)
                           .arg(error.errorString())
                           .toStdString());
  }
  if (!doc.isObject()) r.fail(QStringLiteral("(top level)"), QStringLiteral("expected an object"));
  const QJsonObject root = doc.object();
  if (r.string(root, {}, QStringLiteral("format"), true) != QLatin1String(kProjectFormat))
    r.fail(QStringLiteral("format"), QStringLiteral("expected \"%1\"").arg(kProjectFormat));
  const QJsonValue version = r.member(root, {}, QStringLiteral("version"), true);
  if (!version.isDouble() || version.toDouble() != std::floor(version.toDouble()))
    r.fail(QStringLiteral("version"), QStringLiteral("expected a whole number"));
  if (version.toInt() > kProjectVersion)
    r.fail(QStringLiteral("version"),
           QStringLiteral("version %1 is newer than this SonarGrid reads (%2)")
               .arg(version.toInt())
               .arg(kProjectVersion));

  ProjectState s;
  s.logPath = resolved(r.string(root, {}, QStringLiteral("log"), false), projectPath);
  s.logReading = r.reading(r.object(root, {}, QStringLiteral("log_reading"), false),
                           QStringLiteral("log_reading"), projectPath);
  s.secondLogPath = resolved(r.string(root, {}, QStringLiteral("second_log"), false), projectPath);

  const QJsonObject ref = r.object(root, {}, QStringLiteral("reference"), false);
  if (!ref.isEmpty()) {
    s.referencePath = resolved(
        r.string(ref, QStringLiteral("reference"), QStringLiteral("path"), false), projectPath);
    const QJsonObject inlined =
        r.object(ref, QStringLiteral("reference"), QStringLiteral("inline"), false);
    try {
      if (!inlined.isEmpty()) {
        s.reference = parseReferenceJson(QJsonDocument(inlined).toJson().toStdString(),
                                         file.toStdString() + " (reference.inline)");
        s.referenceModified = true;
      } else if (!s.referencePath.isEmpty()) {
        s.reference = readReference(QDir::toNativeSeparators(s.referencePath).toStdString());
      } else {
        r.fail(QStringLiteral("reference"), QStringLiteral("needs a path or an inline map"));
      }
    } catch (const LogError& e) {
      r.fail(QStringLiteral("reference"), QString::fromUtf8(e.what()));
    }
  }

  const QJsonObject mapping = r.object(root, {}, QStringLiteral("mapping"), true);
  s.settings = r.settings(mapping, QStringLiteral("mapping"));
  s.cellSize = r.cell(mapping, QStringLiteral("mapping"));

  if (root.contains(QStringLiteral("overlays"))) {
    s.overlays = {};
    const QJsonArray overlays = r.array(root, {}, QStringLiteral("overlays"));
    for (qsizetype i = 0; i < overlays.size(); ++i) {
      const QString name = overlays[i].toString();
      bool known = false;
      for (const OverlayName& o : kOverlayNames)
        if (name == QLatin1String(o.name)) {
          s.overlays.setFlag(o.overlay);
          known = true;
        }
      if (!known)
        r.fail(QStringLiteral("overlays[%1]").arg(i),
               QStringLiteral("unknown overlay \"%1\"").arg(name));
    }
  }

  const QJsonObject view = r.object(root, {}, QStringLiteral("view"), false);
  if (!view.isEmpty()) {
    const QJsonArray centre = r.array(view, QStringLiteral("view"), QStringLiteral("centre"));
    if (centre.size() != 2 || !centre[0].isDouble() || !centre[1].isDouble())
      r.fail(QStringLiteral("view.centre"), QStringLiteral("expected [x, y] in metres"));
    ui::ViewTransform v;
    v.centre = Position(centre[0].toDouble(), centre[1].toDouble());
    v.pixelsPerMetre = r.number(view, QStringLiteral("view"), QStringLiteral("pixels_per_metre"));
    if (!(v.pixelsPerMetre > 0.0))
      r.fail(QStringLiteral("view.pixels_per_metre"), QStringLiteral("must be positive"));
    s.view = v;
  }

  const QJsonArray pinned = r.array(root, {}, QStringLiteral("pinned"));
  for (qsizetype i = 0; i < pinned.size(); ++i) {
    const QString field = QStringLiteral("pinned[%1]").arg(i);
    if (!pinned[i].isObject()) r.fail(field, QStringLiteral("expected an object"));
    const QJsonObject o = pinned[i].toObject();
    PinnedRow row;
    row.label = r.string(o, field, QStringLiteral("label"), false);
    row.settings = r.settings(o, field);
    row.cellSize = r.cell(o, field);
    s.pinnedRows.push_back(std::move(row));
  }

  const QJsonObject sweep = r.object(root, {}, QStringLiteral("sweep"), false);
  if (!sweep.isEmpty()) {
    const QString f = QStringLiteral("sweep");
    s.sweep.model = r.string(sweep, f, QStringLiteral("model"), true).toStdString();
    s.sweep.rule = r.string(sweep, f, QStringLiteral("rule"), true).toStdString();
    try {
      (void)defaultParameters(s.sweep.model, s.sweep.rule);
    } catch (const std::exception& e) {
      r.fail(f, QString::fromUtf8(e.what()));
    }
    if (!compatibility(s.sweep.model, s.sweep.rule).allowed)
      r.fail(QStringLiteral("sweep.rule"),
             QString::fromStdString(compatibility(s.sweep.model, s.sweep.rule).reason));
    s.sweep.pose = r.pose(sweep, f);
    s.sweep.parameterGrid = r.string(sweep, f, QStringLiteral("grid"), false,
                                     QString::fromStdString(s.sweep.parameterGrid))
                                .toStdString();
    if (s.sweep.parameterGrid != "paper002-table1")
      r.fail(QStringLiteral("sweep.grid"), QStringLiteral("unknown parameter grid \"%1\"")
                                               .arg(QString::fromStdString(s.sweep.parameterGrid)));
    const QJsonObject base = r.object(sweep, f, QStringLiteral("base"), false);
    for (auto it = base.begin(); it != base.end(); ++it) {
      if (!it.value().isDouble())
        r.fail(QStringLiteral("sweep.base.") + it.key(), QStringLiteral("expected a number"));
      s.sweep.base[it.key().toStdString()] = it.value().toDouble();
    }
    const QJsonValue second = sweep.value(QStringLiteral("use_second_run"));
    if (!second.isUndefined() && !second.isBool())
      r.fail(QStringLiteral("sweep.use_second_run"), QStringLiteral("expected true or false"));
    s.sweep.useSecondRun = second.toBool(true);
    // The sweep view's choice, in `sonargrid-cli sweep`'s grammar: a part that no longer applies
    // to the model and rule (checked as the CLI checks it) is left out and named, the rest opens.
    auto readTexts = [&](const QString& key, std::vector<std::string>& out) {
      if (sweep.value(key).isUndefined()) return;
      const QJsonArray list = r.array(sweep, f, key);
      out.clear();
      for (qsizetype i = 0; i < list.size(); ++i) {
        const QString field = QStringLiteral("sweep.%1[%2]").arg(key).arg(i);
        if (!list[i].isString()) r.fail(field, QStringLiteral("expected a string"));
        out.push_back(list[i].toString().toStdString());
      }
    };
    readTexts(QStringLiteral("axes"), s.sweep.axes);
    readTexts(QStringLiteral("ties"), s.sweep.ties);
    readTexts(QStringLiteral("metrics"), s.sweep.metrics);
    const QStringList left = keepApplicable(s.sweep);
    if (dropped) *dropped << left;
  }
  return s;
}

ProjectState readProject(const QString& projectPath, QStringList* dropped) {
  QFile f(projectPath);
  if (!f.open(QIODevice::ReadOnly))
    throw ProjectError(
        (QDir::toNativeSeparators(projectPath) + QStringLiteral(": ") + f.errorString())
            .toStdString());
  return parseProject(f.readAll(), projectPath, dropped);
}

void writeProject(const ProjectState& state, const QString& projectPath, ProjectPaths paths) {
  const QByteArray bytes = projectJson(state, projectPath, paths);
  try {
    writeFileAtomically(
        QDir::toNativeSeparators(projectPath).toStdString(),
        std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  } catch (const FileWriteError& e) {
    throw ProjectError(e.what());
  }
}

}  // namespace sg::app
