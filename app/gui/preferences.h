// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The app's preferences: typed QSettings keys, kept apart from the document (DESIGN.md, "The
// app"), and the Settings ▸ Preferences dialog that edits them.

#include <QDialog>
#include <QSettings>
#include <QString>
#include <QVariant>

class QCheckBox;
class QLabel;
class QSpinBox;

namespace sg::app {

// One QSettings key with its type and the value it has when never set (or set to something that
// does not convert to T).
template <class T>
class Preference {
 public:
  constexpr Preference(const char* key, T fallback) : key_(key), fallback_(fallback) {}
  const char* key() const { return key_; }
  T fallback() const { return fallback_; }
  T value() const {
    const QVariant v = QSettings().value(QString::fromLatin1(key_));
    return v.isValid() && v.canConvert<T>() ? v.value<T>() : fallback_;
  }
  void set(const T& value) const { QSettings().setValue(QString::fromLatin1(key_), value); }

 private:
  const char* key_;
  T fallback_;
};

namespace preferences {
// Threads mapping may use (core/sonargrid/base/concurrency.h); 0: automatic, i.e.
// SONARGRID_THREADS, else the CPUs the process may run on.
inline constexpr Preference<int> kMappingThreads{"performance/mappingThreads", 0};
// Map with the fast engine (docs/models.md, "Exact and fast engines"): a cone model's Bayes cells
// in four bytes instead of eight. Off: the exact engine.
inline constexpr Preference<bool> kFastEngine{"performance/fastEngine", false};
}  // namespace preferences

// Gives the core's thread policy the stored Mapping threads (at start, and when it changes). A
// stored value outside 0 .. kMaxThreads counts as automatic. Returns the count now in force.
unsigned applyMappingThreads();

// What "automatic" means here, for the dialog and the log: "N, from SONARGRID_THREADS" or "N, the
// CPUs this process may use" (and, for a bad SONARGRID_THREADS, that it is passed over and why).
QString automaticThreadsDescription();

// Settings ▸ Preferences: the Mapping threads spin box (0 = automatic) and the engine. OK stores
// them and applies the threads; the window applies the engine (MainWindow::applyEngine).
class PreferencesDialog : public QDialog {
  Q_OBJECT

 public:
  explicit PreferencesDialog(QWidget* parent = nullptr);
  QSpinBox* mappingThreads() const { return threads_; }
  QCheckBox* fastEngine() const { return fast_; }

  void accept() override;

 private:
  QSpinBox* threads_;
  QCheckBox* fast_;
};

}  // namespace sg::app
