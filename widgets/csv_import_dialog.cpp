// SPDX-License-Identifier: GPL-3.0-or-later
#include "csv_import_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRegularExpression>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <map>
#include <stdexcept>

#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"

namespace sg::ui {
namespace {

// Role combo data: the roles below kSonarBase, sonar k as kSonarBase + k.
constexpr int kSonarBase = 100;
constexpr int kMaxColumns = 200;  // more columns than any sonar ring has

QComboBox* unitCombo(QWidget* parent, const QStringList& labels, const QStringList& values) {
  auto* c = new QComboBox(parent);
  for (int i = 0; i < labels.size(); ++i) c->addItem(labels[i], values[i]);
  return c;
}

void select(QComboBox* c, const QVariant& value) {
  const int i = c->findData(value);
  if (i >= 0) c->setCurrentIndex(i);
}

QString lengthName(LengthUnit u) {
  return u == LengthUnit::Millimetre   ? QStringLiteral("mm")
         : u == LengthUnit::Centimetre ? QStringLiteral("cm")
                                       : QStringLiteral("m");
}

QString angleName(AngleUnit u) {
  return u == AngleUnit::TenthDegree ? QStringLiteral("ddeg")
         : u == AngleUnit::Degree    ? QStringLiteral("deg")
                                     : QStringLiteral("rad");
}

}  // namespace

CsvImportDialog::CsvImportDialog(const QString& path, QWidget* parent)
    : QDialog(parent), path_(path) {
  setWindowTitle(tr("Import CSV log — %1").arg(QFileInfo(path).fileName()));

  header_ = new QSpinBox(this);
  header_->setRange(0, 1000);
  header_->setToolTip(tr("Lines skipped at the top of the log (and of the poses file)"));
  delimiter_ = unitCombo(
      this, {tr("from the first row"), tr("comma"), tr("semicolon"), tr("blanks")},
      {QString(), QStringLiteral("comma"), QStringLiteral("semicolon"), QStringLiteral("blank")});
  length_ = unitCombo(this, {tr("metres"), tr("centimetres"), tr("millimetres")},
                      {QStringLiteral("m"), QStringLiteral("cm"), QStringLiteral("mm")});
  range_ = unitCombo(this, {tr("as x, y"), tr("metres"), tr("centimetres"), tr("millimetres")},
                     {QString(), QStringLiteral("m"), QStringLiteral("cm"), QStringLiteral("mm")});
  angle_ = unitCombo(this, {tr("radians"), tr("degrees"), tr("tenths of a degree")},
                     {QStringLiteral("rad"), QStringLiteral("deg"), QStringLiteral("ddeg")});
  timeUnit_ = unitCombo(this, {tr("seconds"), tr("milliseconds"), tr("microseconds")},
                        {QStringLiteral("s"), QStringLiteral("ms"), QStringLiteral("us")});
  noEcho_ = new QLineEdit(this);
  noEcho_->setPlaceholderText(tr("e.g. 5110"));
  noEcho_->setToolTip(tr("Raw range values that mean \"no echo\", separated by commas or blanks"));

  robot_ = new QComboBox(this);
  for (const std::string& name : SonarRing::presetNames())
    robot_->addItem(QString::fromStdString(name), QString::fromStdString(name));
  robot_->addItem(tr("geometry file…"), QString());
  geometry_ = new QLineEdit(this);
  geometry_->setPlaceholderText(tr("sonar geometry file"));
  auto* browseGeometry = new QPushButton(tr("Browse…"), this);
  poses_ = new QLineEdit(this);
  poses_->setPlaceholderText(tr("none: the pose columns of the log"));
  auto* browsePoses = new QPushButton(tr("Browse…"), this);

  auto* fileBox = new QGroupBox(tr("Rows"), this);
  auto* fileForm = new QFormLayout(fileBox);
  fileForm->addRow(tr("Header lines:"), header_);
  fileForm->addRow(tr("Delimiter:"), delimiter_);
  fileForm->addRow(tr("No-echo values:"), noEcho_);

  auto* unitBox = new QGroupBox(tr("Units"), this);
  auto* unitForm = new QFormLayout(unitBox);
  unitForm->addRow(tr("x, y:"), length_);
  unitForm->addRow(tr("Ranges:"), range_);
  unitForm->addRow(tr("θ:"), angle_);
  unitForm->addRow(tr("Time:"), timeUnit_);

  auto* robotBox = new QGroupBox(tr("Robot"), this);
  auto* robotForm = new QFormLayout(robotBox);
  robotForm->addRow(tr("Sonar ring:"), robot_);
  auto* geometryRow = new QHBoxLayout;
  geometryRow->addWidget(geometry_, 1);
  geometryRow->addWidget(browseGeometry);
  robotForm->addRow(tr("Geometry:"), geometryRow);
  auto* posesRow = new QHBoxLayout;
  posesRow->addWidget(poses_, 1);
  posesRow->addWidget(browsePoses);
  robotForm->addRow(tr("Poses file:"), posesRow);

  auto* settingsRow = new QHBoxLayout;
  settingsRow->addWidget(fileBox, 1);
  settingsRow->addWidget(unitBox, 1);
  settingsRow->addWidget(robotBox, 2);

  table_ = new QTableWidget(this);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setMinimumHeight(260);

  spec_ = new QLineEdit(this);
  spec_->setReadOnly(true);
  spec_->setToolTip(tr("The same mapping as sonargrid-cli --columns"));
  result_ = new QLabel(this);
  result_->setWordWrap(true);
  result_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Load"));
  connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);

  auto* specRow = new QHBoxLayout;
  specRow->addWidget(new QLabel(tr("--columns"), this));
  specRow->addWidget(spec_, 1);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(settingsRow);
  layout->addWidget(new QLabel(
      tr("Preview of the first rows. Choose what each column holds in the top row."), this));
  layout->addWidget(table_, 1);
  layout->addLayout(specRow);
  layout->addWidget(result_);
  layout->addWidget(buttons_);
  resize(900, 640);

  readPreview();
  // A first row of names over rows of numbers is a header (the user can change it).
  for (int i = 0; i + 1 < lines_.size(); ++i) {
    if (lines_[i].trimmed().isEmpty() || lines_[i].trimmed().startsWith(QLatin1Char('#'))) continue;
    bool numbers = true;
    for (const QString& c : cells(lines_[i])) {
      bool ok = false;
      c.toDouble(&ok);
      numbers = numbers && ok;
    }
    if (!numbers) header_->setValue(i + 1);
    break;
  }
  // A common layout to start from: time, x, y, θ, then the sonars in ring order.
  {
    building_ = true;
    fillTable();
    for (int c = 0; c < columnCount(); ++c) {
      if (c < 4)
        setRole(c, static_cast<Role>(c + 1));
      else
        setRole(c, Role::Sonar, c - 4);
    }
    building_ = false;
  }

  const auto changed = [this] { update(); };
  connect(header_, &QSpinBox::valueChanged, this, [this] {
    fillTable();
    update();
  });
  connect(delimiter_, &QComboBox::currentIndexChanged, this, [this] {
    fillTable();
    update();
  });
  for (QComboBox* c : {length_, range_, angle_, timeUnit_})
    connect(c, &QComboBox::currentIndexChanged, this, changed);
  connect(robot_, &QComboBox::currentIndexChanged, this, [this] {
    geometry_->setEnabled(robot_->currentData().toString().isEmpty());
    update();
  });
  geometry_->setEnabled(false);
  connect(noEcho_, &QLineEdit::textChanged, this, changed);
  connect(geometry_, &QLineEdit::textChanged, this, changed);
  connect(poses_, &QLineEdit::textChanged, this, changed);
  connect(browseGeometry, &QPushButton::clicked, this, &CsvImportDialog::browseGeometry);
  connect(browsePoses, &QPushButton::clicked, this, &CsvImportDialog::browsePoses);
  update();
}

void CsvImportDialog::readPreview() {
  QFile f(path_);
  if (!f.open(QIODevice::ReadOnly)) return;  // the result line says why (from the core)
  // Enough lines for a header of any sensible size and the preview rows.
  while (lines_.size() < 1000 + kPreviewRows && !f.atEnd()) {
    QString line = QString::fromUtf8(f.readLine(64 * 1024));
    while (line.endsWith(QLatin1Char('\n')) || line.endsWith(QLatin1Char('\r'))) line.chop(1);
    lines_.push_back(line);
  }
}

char CsvImportDialog::effectiveDelimiter() const {
  const QString d = delimiter_->currentData().toString();
  if (d == QLatin1String("comma")) return ',';
  if (d == QLatin1String("semicolon")) return ';';
  if (d == QLatin1String("blank")) return ' ';
  // As the core decides: the first data row (after the header, comments aside).
  for (int i = header_->value(); i < lines_.size(); ++i) {
    const QString line = lines_[i].trimmed();
    if (line.isEmpty() || line.startsWith(QLatin1Char('#'))) continue;
    return line.contains(QLatin1Char(',')) ? ',' : line.contains(QLatin1Char(';')) ? ';' : ' ';
  }
  return ',';
}

QStringList CsvImportDialog::cells(const QString& line) const {
  const char d = effectiveDelimiter();
  if (d == ' ') return line.split(QRegularExpression(QStringLiteral("\\s+")), Qt::SkipEmptyParts);
  QStringList out = line.split(QLatin1Char(d));
  for (QString& c : out) c = c.trimmed();
  return out;
}

void CsvImportDialog::fillTable() {
  // The previous roles stay with their columns.
  QList<int> kept;
  for (QComboBox* c : roles_) kept.push_back(c->currentData().toInt());
  roles_.clear();

  QList<QStringList> rows;
  QStringList rowNames;
  for (int i = 0; i < lines_.size() && rows.size() < kPreviewRows + header_->value(); ++i) {
    rows.push_back(i < header_->value() || lines_[i].trimmed().startsWith(QLatin1Char('#'))
                       ? QStringList{lines_[i]}
                       : cells(lines_[i]));
    rowNames.push_back(QString::number(i + 1));
  }
  int columns = 0;
  for (int i = 0; i < rows.size(); ++i)
    if (i >= header_->value() && rows[i].size() > 1)
      columns = std::max(columns, int(rows[i].size()));
  columns = std::clamp(columns, 1, kMaxColumns);

  table_->clear();
  table_->setColumnCount(columns);
  table_->setRowCount(int(rows.size()) + 1);
  QStringList columnNames;
  for (int c = 0; c < columns; ++c) columnNames.push_back(tr("column %1").arg(c + 1));
  table_->setHorizontalHeaderLabels(columnNames);
  table_->setVerticalHeaderLabels(QStringList{tr("role")} + rowNames);
  for (int c = 0; c < columns; ++c) {
    auto* combo = new QComboBox(table_);
    combo->addItem(tr("ignore"), int(Role::Ignore));
    combo->addItem(tr("time"), int(Role::Time));
    combo->addItem(tr("x"), int(Role::X));
    combo->addItem(tr("y"), int(Role::Y));
    combo->addItem(tr("θ"), int(Role::Theta));
    for (int k = 0; k < columns; ++k) combo->addItem(tr("sonar %1").arg(k), kSonarBase + k);
    if (c < kept.size()) select(combo, kept[c]);
    connect(combo, &QComboBox::currentIndexChanged, this, [this] { update(); });
    table_->setCellWidget(0, c, combo);
    roles_.push_back(combo);
  }
  for (int r = 0; r < rows.size(); ++r) {
    const bool raw = rows[r].size() == 1;  // header or comment lines span the row as they are
    for (int c = 0; c < rows[r].size() && c < columns; ++c) {
      auto* item = new QTableWidgetItem(rows[r][c]);
      if (r < header_->value() || raw)
        item->setForeground(palette().color(QPalette::PlaceholderText));
      table_->setItem(r + 1, c, item);
    }
    if (raw && columns > 1) table_->setSpan(r + 1, 0, 1, columns);
  }
}

int CsvImportDialog::columnCount() const {
  return int(roles_.size());
}

void CsvImportDialog::setRole(int column, Role role, int sonar) {
  if (column < 0 || column >= roles_.size()) return;
  select(roles_[column], role == Role::Sonar ? kSonarBase + sonar : int(role));
}

CsvImportDialog::Role CsvImportDialog::role(int column) const {
  if (column < 0 || column >= roles_.size()) return Role::Ignore;
  const int v = roles_[column]->currentData().toInt();
  return v >= kSonarBase ? Role::Sonar : static_cast<Role>(v);
}

void CsvImportDialog::setHeaderLines(int lines) {
  header_->setValue(lines);
}

void CsvImportDialog::setDelimiter(char delimiter) {
  select(delimiter_, delimiter == ','   ? QStringLiteral("comma")
                     : delimiter == ';' ? QStringLiteral("semicolon")
                     : delimiter == ' ' ? QStringLiteral("blank")
                                        : QString());
}

void CsvImportDialog::setLengthUnit(LengthUnit unit) {
  select(length_, lengthName(unit));
}

void CsvImportDialog::setRangeUnit(std::optional<LengthUnit> unit) {
  select(range_, unit ? lengthName(*unit) : QString());
}

void CsvImportDialog::setAngleUnit(AngleUnit unit) {
  select(angle_, angleName(unit));
}

void CsvImportDialog::setTimeUnit(const QString& unit) {
  select(timeUnit_, unit);
}

void CsvImportDialog::setNoEcho(const QString& values) {
  noEcho_->setText(values);
}

void CsvImportDialog::setRobotPreset(const QString& name) {
  select(robot_, name);
}

void CsvImportDialog::setGeometryFile(const QString& path) {
  select(robot_, QString());
  geometry_->setText(path);
}

void CsvImportDialog::setPosesFile(const QString& path) {
  poses_->setText(path);
}

QString CsvImportDialog::columnSpec() const {
  QStringList items;
  if (header_->value() > 0) items << QStringLiteral("header=%1").arg(header_->value());
  std::map<int, int> sonars;  // sonar -> 1-based column
  const char* names[] = {"", "time", "x", "y", "theta"};
  for (int r = int(Role::Time); r <= int(Role::Theta); ++r)
    for (int c = 0; c < roles_.size(); ++c)
      if (roles_[c]->currentData().toInt() == r)
        items << QStringLiteral("%1=%2").arg(QLatin1String(names[r])).arg(c + 1);
  for (int c = 0; c < roles_.size(); ++c) {
    const int v = roles_[c]->currentData().toInt();
    if (v >= kSonarBase) sonars.emplace(v - kSonarBase, c + 1);
  }
  // Runs of consecutive columns in ring order become FIRST-LAST.
  for (auto it = sonars.begin(); it != sonars.end();) {
    const int first = it->second;
    int last = first;
    for (++it; it != sonars.end() && it->second == last + 1; ++it) ++last;
    items << (first == last ? QStringLiteral("sonars=%1").arg(first)
                            : QStringLiteral("sonars=%1-%2").arg(first).arg(last));
  }
  if (const QString l = length_->currentData().toString(); l != QLatin1String("m"))
    items << QStringLiteral("length=") + l;
  if (const QString r = range_->currentData().toString(); !r.isEmpty())
    items << QStringLiteral("range=") + r;
  if (const QString a = angle_->currentData().toString(); a != QLatin1String("rad"))
    items << QStringLiteral("angle=") + a;
  if (const QString t = timeUnit_->currentData().toString(); t != QLatin1String("s"))
    items << QStringLiteral("time_unit=") + t;
  for (const QString& v :
       noEcho_->text().split(QRegularExpression(QStringLiteral("[,;\\s]+")), Qt::SkipEmptyParts))
    items << QStringLiteral("noecho=") + v;
  if (const QString d = delimiter_->currentData().toString(); !d.isEmpty())
    items << QStringLiteral("delimiter=") + d;
  return items.join(QLatin1Char(','));
}

QString CsvImportDialog::buildOptions(LogOptions& out) const {
  // Sonar k must be given to exactly one column, k = 0 .. n-1.
  std::map<int, int> sonars;
  for (int c = 0; c < roles_.size(); ++c) {
    const int v = roles_[c]->currentData().toInt();
    if (v < kSonarBase) continue;
    if (!sonars.emplace(v - kSonarBase, c + 1).second)
      return tr("sonar %1 is given to columns %2 and %3")
          .arg(v - kSonarBase)
          .arg(sonars[v - kSonarBase])
          .arg(c + 1);
  }
  int expected = 0;
  for (const auto& [k, column] : sonars) {
    if (k != expected)
      return tr("sonar %1 has no column (sonars are numbered from 0)").arg(expected);
    ++expected;
  }
  for (int r = int(Role::Time); r <= int(Role::Theta); ++r) {
    int first = 0;
    for (int c = 0; c < roles_.size(); ++c) {
      if (roles_[c]->currentData().toInt() != r) continue;
      if (first != 0)
        return tr("%1 is given to columns %2 and %3")
            .arg(roles_[c]->currentText())
            .arg(first)
            .arg(c + 1);
      first = c + 1;
    }
  }
  out = LogOptions{};
  out.format = LogFormat::Csv;
  try {
    out.csv = parseCsvLayout(columnSpec().toStdString());
  } catch (const std::invalid_argument& e) {
    return QString::fromStdString(e.what());
  }
  const QString preset = robot_->currentData().toString();
  if (!preset.isEmpty()) {
    SonarRing ring;
    if (SonarRing::preset(preset.toStdString(), ring)) out.ring = ring;
  } else if (geometry_->text().isEmpty()) {
    return tr("choose a sonar ring preset or a geometry file");
  } else {
    try {
      out.ring = readSonarGeometry(QDir::toNativeSeparators(geometry_->text()).toStdString());
    } catch (const std::exception& e) {
      return QString::fromStdString(e.what());
    }
  }
  out.posesPath = QDir::toNativeSeparators(poses_->text()).toStdString();
  return QString();
}

void CsvImportDialog::update() {
  if (building_) return;
  spec_->setText(columnSpec());
  LogOptions o;
  QString error = buildOptions(o);
  previewOk_ = false;
  options_.reset();
  if (error.isEmpty()) {
    // The header and the preview rows, parsed by the core exactly as the whole file will be.
    const int rows = std::min(int(lines_.size()), header_->value() + kPreviewRows);
    const QByteArray bytes =
        QStringList(lines_.mid(0, rows)).join(QLatin1Char('\n')).toUtf8() + '\n';
    try {
      const Dataset d = parseLog(std::string_view(bytes.constData(), std::size_t(bytes.size())),
                                 QDir::toNativeSeparators(path_).toStdString(), o);
      result_->setText(tr("Preview: %1 scans, %2 readings in the first %3 rows")
                           .arg(d.scans.size())
                           .arg(d.readingCount())
                           .arg(rows - header_->value()));
      previewOk_ = true;
      options_ = o;
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
  }
  if (!error.isEmpty()) result_->setText(tr("Error: %1").arg(error));
  result_->setStyleSheet(previewOk_ ? QString() : QStringLiteral("color: #b00020;"));
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(previewOk_);
}

QString CsvImportDialog::result() const {
  return result_->text();
}

void CsvImportDialog::browseGeometry() {
  const QString file =
      QFileDialog::getOpenFileName(this, tr("Sonar Geometry"), QFileInfo(path_).absolutePath());
  if (!file.isEmpty()) setGeometryFile(file);
}

void CsvImportDialog::browsePoses() {
  const QString file =
      QFileDialog::getOpenFileName(this, tr("Poses File"), QFileInfo(path_).absolutePath());
  if (!file.isEmpty()) setPosesFile(file);
}

}  // namespace sg::ui
