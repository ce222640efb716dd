// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Autosave: while the document has unsaved changes, a project file with its whole state (unsaved
// reference edits inline, the settings, absolute log paths) is written atomically every 30 s to
// `session-<pid>.sgproj` in the autosave folder, beside a lock file the session holds. A file whose
// lock no running session holds was left by a session that crashed: the next start offers to
// recover it. Saving the project and quitting cleanly remove the file.
//
// SONARGRID_AUTOSAVE_MS sets the interval and SONARGRID_AUTOSAVE_DIR the folder (tests); by
// default the folder is "autosave" under QStandardPaths::AppDataLocation.

#include <QObject>
#include <QString>
#include <QStringList>
#include <functional>
#include <memory>

class QLockFile;
class QTimer;

namespace sg::app {

class Document;
struct ProjectState;

class Autosave : public QObject {
  Q_OBJECT

 public:
  // `state` gives what to save (the Document's state with the view as shown now).
  Autosave(Document* document, std::function<ProjectState()> state, QObject* parent = nullptr);
  // A clean exit: the file and the lock go.
  ~Autosave() override;

  static QString directory();
  static int intervalMs();

  // This session's file (written or not yet).
  QString filePath() const;
  // Writes the file now when the document is modified; true when written.
  bool saveNow();
  // Removes this session's file (after a save: nothing unsaved is left to recover).
  void remove();
  void setEnabled(bool on);

  // Autosave files whose session is no longer running, newest first.
  static QStringList orphans();
  // Deletes a crashed session's file and its lock.
  static void discard(const QString& file);
  // The project file a crashed session had open (empty: untitled), as its autosave records it.
  static QString originalProject(const QString& file);

 signals:
  void failed(const QString& message);

 private:
  bool lockSession();

  Document* document_;
  std::function<ProjectState()> state_;
  QTimer* timer_;
  std::unique_ptr<QLockFile> lock_;
  bool enabled_ = true;
};

}  // namespace sg::app
