// SPDX-License-Identifier: GPL-3.0-or-later
#include "autosave.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
#include <QStandardPaths>
#include <QTimer>
#include <algorithm>

#include "document.h"
#include "project_file.h"
#include "sonargrid/base/atomic_file.h"

namespace sg::app {
namespace {

constexpr int kDefaultIntervalMs = 30 * 1000;

QString lockPathFor(const QString& file) {
  return file.left(file.size() - QFileInfo(file).suffix().size()) + QStringLiteral("lock");
}

}  // namespace

Autosave::Autosave(Document* document, std::function<ProjectState()> state, QObject* parent)
    : QObject(parent), document_(document), state_(std::move(state)), timer_(new QTimer(this)) {
  timer_->setInterval(intervalMs());
  connect(timer_, &QTimer::timeout, this, &Autosave::saveNow);
  // The clock runs only while there is something unsaved. Back at the saved state (a save, or
  // undo to it) there is nothing to recover: the file goes.
  connect(document_, &Document::modifiedChanged, this, [this](bool modified) {
    if (modified && enabled_) {
      timer_->start();
    } else if (!modified) {
      timer_->stop();
      remove();
    }
  });
}

Autosave::~Autosave() {
  remove();
}

QString Autosave::directory() {
  const QString env = qEnvironmentVariable("SONARGRID_AUTOSAVE_DIR");
  if (!env.isEmpty()) return env;
  return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
         QStringLiteral("/autosave");
}

int Autosave::intervalMs() {
  bool ok = false;
  const int ms = qEnvironmentVariableIntValue("SONARGRID_AUTOSAVE_MS", &ok);
  return ok && ms > 0 ? ms : kDefaultIntervalMs;
}

QString Autosave::filePath() const {
  return directory() + QStringLiteral("/session-%1.sgproj").arg(QCoreApplication::applicationPid());
}

void Autosave::setEnabled(bool on) {
  enabled_ = on;
  if (!on)
    timer_->stop();
  else if (document_->isModified())
    timer_->start();
}

bool Autosave::lockSession() {
  if (lock_) return true;
  if (!QDir().mkpath(directory())) {
    emit failed(tr("Autosave: cannot create the folder %1").arg(directory()));
    return false;
  }
  auto lock = std::make_unique<QLockFile>(lockPathFor(filePath()));
  lock->setStaleLockTime(0);  // held for the whole session: only a dead process makes it stale
  if (!lock->tryLock(0)) {
    emit failed(tr("Autosave: cannot lock %1").arg(lockPathFor(filePath())));
    return false;
  }
  lock_ = std::move(lock);
  return true;
}

bool Autosave::saveNow() {
  if (!enabled_ || !document_->isModified() || !lockSession()) return false;
  ProjectState state = state_();
  QByteArray bytes = projectJson(state, filePath(), ProjectPaths::Absolute);
  // Which project the session had open, so recovery can offer to save over it.
  QJsonObject root = QJsonDocument::fromJson(bytes).object();
  root.insert(QStringLiteral("autosave_of"), document_->projectPath());
  bytes = QJsonDocument(root).toJson(QJsonDocument::Indented);
  try {
    writeFileAtomically(
        QDir::toNativeSeparators(filePath()).toStdString(),
        std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  } catch (const FileWriteError& e) {
    emit failed(tr("Autosave failed: %1").arg(QString::fromUtf8(e.what())));
    return false;
  }
  return true;
}

void Autosave::remove() {
  QFile::remove(filePath());
  if (lock_) {
    lock_->unlock();
    lock_.reset();
  }
}

QStringList Autosave::orphans() {
  const QDir dir(directory());
  QFileInfoList files = dir.entryInfoList({QStringLiteral("session-*.sgproj")}, QDir::Files);
  std::sort(files.begin(), files.end(), [](const QFileInfo& a, const QFileInfo& b) {
    return a.lastModified() > b.lastModified();
  });
  QStringList out;
  for (const QFileInfo& f : files) {
    // A running session (this one included) holds its lock; a crashed one's lock is stale, and
    // taking it shows the file is orphaned.
    QLockFile lock(lockPathFor(f.absoluteFilePath()));
    lock.setStaleLockTime(0);
    if (!lock.tryLock(0)) continue;
    lock.unlock();
    out << f.absoluteFilePath();
  }
  return out;
}

void Autosave::discard(const QString& file) {
  QFile::remove(file);
  QFile::remove(lockPathFor(file));
}

QString Autosave::originalProject(const QString& file) {
  QFile f(file);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QJsonDocument::fromJson(f.readAll())
      .object()
      .value(QStringLiteral("autosave_of"))
      .toString();
}

}  // namespace sg::app
