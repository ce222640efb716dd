// SPDX-License-Identifier: GPL-3.0-or-later
// Projects: open, save, the unsaved-changes question, and recovery of a crashed session's autosave.
#include <QApplication>
#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
#include <cstdio>

#include "autosave.h"
#include "document.h"
#include "main_window.h"
#include "project_file.h"

namespace sg::app {
namespace {

// No dialog may block where nobody can answer it: tests and --screenshot run offscreen.
bool headless() {
  const QString platform = QApplication::platformName();
  return platform == QLatin1String("offscreen") || platform == QLatin1String("minimal");
}

}  // namespace

ProjectState MainWindow::projectState() const {
  ProjectState state = document_->state();
  if (view_->map()) state.view = view_->view();
  return state;
}

void MainWindow::sayDropped(const QString& path, const QStringList& dropped) {
  if (dropped.isEmpty()) return;
  // The rest of the project opened; what no longer applied is named, on the status bar and on
  // stderr (a headless run has no status bar to read).
  const QString text = tr("%1: left out sweep settings that no longer apply: %2")
                           .arg(QDir::toNativeSeparators(path), dropped.join(QStringLiteral("; ")));
  statusBar()->showMessage(text, 20000);
  std::fprintf(stderr, "sonargrid: %s\n", qPrintable(text));
}

bool MainWindow::openProject(const QString& path, bool quiet) {
  ProjectState state;
  QStringList dropped;
  try {
    state = readProject(path, &dropped);
  } catch (const ProjectError& e) {
    return reportError(tr("Cannot open project"), QString::fromUtf8(e.what()), quiet);
  }
  adoptProject(path, state, false, quiet);
  sayDropped(path, dropped);
  if (state.logPath.isEmpty()) return true;
  return !quiet || waitForLoad();
}

void MainWindow::adoptProject(const QString& path, const ProjectState& state, bool modified,
                              bool quiet) {
  if (state.logPath.isEmpty()) {
    // Nothing to load: the project replaces the document now, keeping the open log.
    ProjectState s = state;
    s.logPath = document_->logPath();
    s.logReading = document_->logReading();
    document_->restore(s, modified);
    document_->setProjectPath(path);
    if (!path.isEmpty()) rememberRecent(path);
    return;
  }
  // The project becomes the document once its log has loaded; until then the current one stays.
  PendingProject pending;
  pending.path = path;
  pending.logPath = state.logPath;
  pending.state = std::make_shared<ProjectState>(state);
  pending.modified = modified;
  cancelLoad();
  pendingProject_ = pending;
  loadLog(state.logPath, optionsOf(state.logReading), quiet);
}

bool MainWindow::saveProjectAs(const QString& path, bool quiet) {
  try {
    writeProject(projectState(), path);
  } catch (const ProjectError& e) {
    return reportError(tr("Cannot save project"), QString::fromUtf8(e.what()), quiet);
  }
  document_->setProjectPath(path);
  document_->markSaved();
  autosave_->remove();
  rememberRecent(path);
  statusBar()->showMessage(tr("Saved %1").arg(QDir::toNativeSeparators(path)), 5000);
  return true;
}

bool MainWindow::saveProject() {
  if (!document_->projectPath().isEmpty()) return saveProjectAs(document_->projectPath());
  if (headless()) return false;
  const QString path = saveFileName(tr("Save Project"), tr("SonarGrid projects (*.sgproj)"),
                                    QStringLiteral(".sgproj"));
  return !path.isEmpty() && saveProjectAs(path);
}

bool MainWindow::maybeSave() {
  if (!document_->isModified()) return true;
  // SONARGRID_UNSAVED_CHANGES answers for scripts and tests: save, discard or cancel.
  QString answer = qEnvironmentVariable("SONARGRID_UNSAVED_CHANGES");
  if (answer.isEmpty() && headless()) answer = QStringLiteral("discard");
  if (answer.isEmpty()) {
    const auto choice = QMessageBox::warning(
        this, tr("Unsaved Changes"),
        tr("The project has unsaved changes (settings, reference edits, pinned rows). Save "
           "them?"),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    answer = choice == QMessageBox::Save      ? QStringLiteral("save")
             : choice == QMessageBox::Discard ? QStringLiteral("discard")
                                              : QStringLiteral("cancel");
  }
  if (answer == QLatin1String("save")) return saveProject();
  return answer == QLatin1String("discard");
}

bool MainWindow::offerRecovery(const QString& given) {
  const QStringList files = Autosave::orphans();
  if (files.isEmpty()) return false;
  const QString newest = files.front();
  QString answer = given;
  if (answer.isEmpty()) answer = qEnvironmentVariable("SONARGRID_RECOVER");
  if (answer.isEmpty() && headless()) answer = QStringLiteral("keep");
  if (answer.isEmpty()) {
    QMessageBox box(
        QMessageBox::Question, tr("Recover Unsaved Work"),
        tr("SonarGrid did not quit properly. Its autosave from %1 holds unsaved "
           "settings and reference edits. Recover them?")
            .arg(QLocale().toString(QFileInfo(newest).lastModified(), QLocale::ShortFormat)),
        QMessageBox::NoButton, this);
    QPushButton* recover = box.addButton(tr("&Recover"), QMessageBox::AcceptRole);
    QPushButton* discard = box.addButton(tr("&Discard"), QMessageBox::DestructiveRole);
    box.addButton(tr("&Not Now"), QMessageBox::RejectRole);
    box.exec();
    answer = box.clickedButton() == recover   ? QStringLiteral("yes")
             : box.clickedButton() == discard ? QStringLiteral("no")
                                              : QStringLiteral("keep");
  }
  if (answer == QLatin1String("no")) {
    for (const QString& f : files) Autosave::discard(f);
    return false;
  }
  if (answer != QLatin1String("yes")) return false;
  ProjectState state;
  QStringList dropped;
  try {
    state = readProject(newest, &dropped);
  } catch (const ProjectError& e) {
    return reportError(tr("Cannot recover"), QString::fromUtf8(e.what()), false);
  }
  // The recovered work is unsaved: the document stays modified (and autosaved by this session).
  adoptProject(Autosave::originalProject(newest), state, true, false);
  Autosave::discard(newest);
  statusBar()->showMessage(tr("Recovered the unsaved work of a session that did not quit"), 10000);
  sayDropped(newest, dropped);
  return true;
}

}  // namespace sg::app
