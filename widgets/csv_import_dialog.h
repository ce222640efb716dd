// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The import dialog of a generic CSV or whitespace-separated sonar log (docs/user-guide.md,
// "Importing CSV logs"): a preview of the first rows, a role per column (time, x, y, θ, sonar k or
// ignored), the units, the no-echo values, the ring and an optional poses file. It writes the same
// column spec the CLI's --columns takes and lets the core parse it (sg::parseCsvLayout) and the
// preview rows (sg::parseLog); it only splits the raw text into cells for show.

#include <QDialog>
#include <QStringList>
#include <optional>

#include "sonargrid/io/log_options.h"

class QComboBox;
class QDialogButtonBox;
class QLabel;
class QLineEdit;
class QSpinBox;
class QTableWidget;

namespace sg::ui {

class CsvImportDialog : public QDialog {
  Q_OBJECT

 public:
  enum class Role { Ignore, Time, X, Y, Theta, Sonar };

  explicit CsvImportDialog(const QString& path, QWidget* parent = nullptr);

  static constexpr int kPreviewRows = 20;

  // Columns count from 0 here (the spec numbers them from 1).
  void setRole(int column, Role role, int sonar = 0);
  Role role(int column) const;
  int columnCount() const;
  void setHeaderLines(int lines);
  // 0 = decided from the first data row, else ',', ';' or ' '.
  void setDelimiter(char delimiter);
  void setLengthUnit(sg::LengthUnit unit);
  // std::nullopt: the ranges are in the length unit.
  void setRangeUnit(std::optional<sg::LengthUnit> unit);
  void setAngleUnit(sg::AngleUnit unit);
  // "s", "ms" or "us".
  void setTimeUnit(const QString& unit);
  // Raw values separated by commas or blanks, e.g. "5110".
  void setNoEcho(const QString& values);
  // A ring preset name (k2a, p3dx, amigobot) or, with setGeometryFile, a geometry file.
  void setRobotPreset(const QString& name);
  void setGeometryFile(const QString& path);
  void setPosesFile(const QString& path);

  // The --columns spec of the current choices (it may be incomplete: see result()).
  QString columnSpec() const;
  // The options the log loads with; empty while the choices do not parse.
  std::optional<sg::LogOptions> options() const { return options_; }
  // What the core made of the preview rows: "N scans, M readings in the first K rows" or the first
  // error (file:line: field: expected ...).
  QString result() const;
  bool previewParses() const { return previewOk_; }
  QTableWidget* previewTable() const { return table_; }

 private:
  void readPreview();
  void fillTable();
  void update();
  QString buildOptions(sg::LogOptions& out) const;
  char effectiveDelimiter() const;
  QStringList cells(const QString& line) const;
  void browseGeometry();
  void browsePoses();

  QString path_;
  QStringList lines_;  // the raw first lines of the file
  bool building_ = false;
  bool previewOk_ = false;
  std::optional<sg::LogOptions> options_;

  QSpinBox* header_;
  QComboBox* delimiter_;
  QComboBox* length_;
  QComboBox* range_;
  QComboBox* angle_;
  QComboBox* timeUnit_;
  QLineEdit* noEcho_;
  QComboBox* robot_;
  QLineEdit* geometry_;
  QLineEdit* poses_;
  QTableWidget* table_;
  QList<QComboBox*> roles_;
  QLineEdit* spec_;
  QLabel* result_;
  QDialogButtonBox* buttons_;
};

}  // namespace sg::ui
