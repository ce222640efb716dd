// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_editor.h"

#include <QAction>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <stdexcept>

#include "grid_view.h"
#include "reference_edit_model.h"
#include "reference_edit_tool.h"
#include "reference_editor_panel.h"
#include "sonargrid/base/atomic_file.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/reference_json.h"

namespace sg::ui {

ReferenceEditor::ReferenceEditor(QUndoStack* stack, GridView* view, QWidget* parent)
    : QObject(parent), view_(view), parent_(parent) {
  model_ = new ReferenceEditModel(this);
  model_->setUndoStack(stack);
  tool_ = new ReferenceEditTool(model_, this);
  panel_ = new ReferenceEditorPanel(model_, tool_);
  dock_ = new QDockWidget(tr("Reference Editor"), parent);
  dock_->setObjectName(QStringLiteral("referenceEditorDock"));
  dock_->setWidget(panel_);

  editMode_ = new QAction(tr("&Edit Reference Map"), this);
  editMode_->setObjectName(QStringLiteral("editReferenceMode"));
  editMode_->setCheckable(true);
  editMode_->setShortcut(QKeySequence(Qt::Key_E));
  editMode_->setToolTip(
      tr("Draw and move the reference map's corners in the grid view, type tape measurements in "
         "the dock"));
  connect(editMode_, &QAction::toggled, this, &ReferenceEditor::setEditing);
  new_ = new QAction(tr("&New Reference Map"), this);
  connect(new_, &QAction::triggered, this, [this] {
    setReference(ReferenceMap{}, QString());
    setEditing(true);
  });
  open_ = new QAction(tr("Open Reference for &Editing…"), this);
  connect(open_, &QAction::triggered, this, &ReferenceEditor::openDialog);
  save_ = new QAction(tr("&Save Reference Map"), this);
  connect(save_, &QAction::triggered, this, [this] { saveDialog(false); });
  saveAs_ = new QAction(tr("Save Reference Map &As…"), this);
  connect(saveAs_, &QAction::triggered, this, [this] { saveDialog(true); });
  connect(panel_->newButton(), &QPushButton::clicked, new_, &QAction::trigger);
  connect(panel_->openButton(), &QPushButton::clicked, open_, &QAction::trigger);
  connect(panel_->saveButton(), &QPushButton::clicked, save_, &QAction::trigger);
  connect(panel_->saveAsButton(), &QPushButton::clicked, saveAs_, &QAction::trigger);

  connect(model_, &ReferenceEditModel::changed, this, [this] {
    if (!adopting_) emit referenceEdited();
  });
  connect(tool_, &ReferenceEditTool::repaintNeeded, view_, &GridView::toolChanged);
  connect(tool_, &ReferenceEditTool::message, this, &ReferenceEditor::message);
}

ReferenceEditor::~ReferenceEditor() {
  if (view_ && view_->tool() == tool_) view_->setTool(nullptr);
  if (!parent_) delete dock_;  // without a window, nobody else owns it
}

void ReferenceEditor::setUndoStack(QUndoStack* stack) {
  model_->setUndoStack(stack);
}

void ReferenceEditor::setReference(std::optional<ReferenceMap> reference, const QString& path) {
  tool_->cancelDrawing();
  model_->select(-1);
  model_->replaceReference(std::move(reference), path, tr("Open Reference"));
  if (model_->hasReference()) panel_->setEntryUnit(model_->map().unit);
}

void ReferenceEditor::adoptReference(std::optional<ReferenceMap> reference, const QString& path) {
  tool_->cancelDrawing();
  adopting_ = true;
  model_->putReference(reference, path);
  adopting_ = false;
  if (model_->hasReference()) panel_->setEntryUnit(model_->map().unit);
}

const std::optional<ReferenceMap>& ReferenceEditor::reference() const {
  return model_->reference();
}

QString ReferenceEditor::path() const {
  return model_->path();
}

bool ReferenceEditor::open(const QString& path, QString* error) {
  try {
    setReference(readReference(QDir::toNativeSeparators(path).toStdString()), path);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  if (model_->map().raster) {
    emit message(
        tr("%1: an occupancy image; its obstacle cells are kept for scoring, and corner objects "
           "drawn over it are added (it cannot be saved as reference JSON)")
            .arg(QFileInfo(path).fileName()));
  }
  return true;
}

bool ReferenceEditor::save(const QString& path, QString* error) {
  try {
    writeReferenceJson(model_->map(), QDir::toNativeSeparators(path).toStdString());
  } catch (const std::invalid_argument& e) {
    if (error) *error = path + QStringLiteral(": ") + QString::fromStdString(e.what());
    return false;
  } catch (const std::exception& e) {  // FileWriteError names the path
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  model_->setPath(path);
  emit message(tr("Saved %1").arg(path));
  return true;
}

bool ReferenceEditor::editing() const {
  return view_ && view_->tool() == tool_;
}

void ReferenceEditor::setEditing(bool on) {
  if (on == editing() || !view_) return;
  editMode_->setChecked(on);
  if (on) {
    view_->setTool(tool_);
    view_->setCursor(Qt::CrossCursor);
    if (dock_->parentWidget()) {  // in a window (alone, a dock would float as its own window)
      dock_->show();
      dock_->raise();
    }
    emit message(
        tr("Editing the reference map: click corners; Enter ends an object open, C closed; "
           "drag corners; Ctrl+click an edge inserts one; Del deletes; S snaps; E leaves"));
  } else {
    tool_->cancelDrawing();
    view_->setTool(nullptr);
    emit message(tr("Left reference editing"));
  }
}

void ReferenceEditor::report(const QString& title, const QString& text) {
  QMessageBox::warning(parent_, title, text);
}

void ReferenceEditor::openDialog() {
  const QString dir = QSettings().value("files/lastDirectory").toString();
  const QString path =
      QFileDialog::getOpenFileName(parent_, tr("Open Reference Map for Editing"), dir,
                                   tr("Reference maps (*.json *.map *.yaml *.yml);;All files (*)"));
  if (path.isEmpty()) return;
  QString error;
  if (!open(path, &error)) return report(tr("Cannot open reference map"), error);
  setEditing(true);
}

bool ReferenceEditor::saveDialog(bool askPath) {
  QString path = model_->path();
  // An imported ArMap or ROS map is saved as a new JSON file, never over its source.
  if (askPath || path.isEmpty() || QFileInfo(path).suffix().toLower() != QLatin1String("json")) {
    const QString suggested = path.isEmpty() ? QSettings().value("files/lastDirectory").toString()
                                             : QFileInfo(path).path() + QDir::separator() +
                                                   QFileInfo(path).completeBaseName() +
                                                   QStringLiteral(".json");
    path = QFileDialog::getSaveFileName(parent_, tr("Save Reference Map"), suggested,
                                        tr("Reference maps (*.json)"));
    if (path.isEmpty()) return false;
    if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".json");
  }
  QString error;
  if (!save(path, &error)) {
    report(tr("Cannot save reference map"), error);
    return false;
  }
  return true;
}

}  // namespace sg::ui
