// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_editor_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QTableWidget>
#include <QVBoxLayout>

#include "reference_edit_model.h"
#include "reference_edit_tool.h"
#include "typed_length.h"

namespace sg::ui {
namespace {

const LengthUnit kUnits[] = {LengthUnit::Metre, LengthUnit::Centimetre, LengthUnit::Millimetre};

QPushButton* button(const QString& text, const QString& name, QWidget* parent) {
  auto* b = new QPushButton(text, parent);
  b->setObjectName(name);
  b->setAutoDefault(false);
  return b;
}

// Sets a cell's text (and check state) in place: an item is never deleted while its own
// itemChanged signal is being handled.
QTableWidgetItem* cell(QTableWidget* table, int row, int column, Qt::ItemFlags flags) {
  QTableWidgetItem* item = table->item(row, column);
  if (!item) {
    item = new QTableWidgetItem;
    table->setItem(row, column, item);
  }
  item->setFlags(flags);
  return item;
}

constexpr Qt::ItemFlags kEditable = Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsEditable;
constexpr Qt::ItemFlags kReadOnly = Qt::ItemIsEnabled | Qt::ItemIsSelectable;

}  // namespace

ReferenceEditorPanel::ReferenceEditorPanel(ReferenceEditModel* model, ReferenceEditTool* tool,
                                           QWidget* parent)
    : QWidget(parent), model_(model), tool_(tool) {
  auto* layout = new QVBoxLayout(this);

  fileLabel_ = new QLabel(this);
  fileLabel_->setObjectName(QStringLiteral("referenceFile"));
  fileLabel_->setWordWrap(true);
  layout->addWidget(fileLabel_);
  auto* files = new QHBoxLayout;
  newButton_ = button(tr("New"), QStringLiteral("newReference"), this);
  openButton_ = button(tr("Open…"), QStringLiteral("openReference"), this);
  openButton_->setToolTip(
      tr("A sonargrid reference (.json), an ArMap (.map) or a ROS map (.yaml)"));
  saveButton_ = button(tr("Save"), QStringLiteral("saveReference"), this);
  saveAsButton_ = button(tr("Save As…"), QStringLiteral("saveReferenceAs"), this);
  for (QPushButton* b : {newButton_, openButton_, saveButton_, saveAsButton_}) files->addWidget(b);
  layout->addLayout(files);
  snap_ = new QCheckBox(tr("&Snap to corners and grid (S)"), this);
  snap_->setObjectName(QStringLiteral("snap"));
  layout->addWidget(snap_);
  connect(snap_, &QCheckBox::toggled, tool_, &ReferenceEditTool::setSnapping);
  connect(tool_, &ReferenceEditTool::snappingChanged, snap_, &QCheckBox::setChecked);

  auto* objectsBox = new QGroupBox(tr("Objects"), this);
  auto* objectsLayout = new QVBoxLayout(objectsBox);
  objects_ = new QTableWidget(0, 3, objectsBox);
  objects_->setObjectName(QStringLiteral("objects"));
  objects_->setHorizontalHeaderLabels({tr("Name"), tr("Closed"), tr("Corners")});
  objects_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  objects_->verticalHeader()->setVisible(false);
  objects_->setSelectionBehavior(QAbstractItemView::SelectRows);
  objects_->setSelectionMode(QAbstractItemView::SingleSelection);
  objectsLayout->addWidget(objects_);
  auto* objectButtons = new QHBoxLayout;
  newObject_ = button(tr("New Object"), QStringLiteral("newObject"), objectsBox);
  newObject_->setToolTip(tr("Type its corners below, or click them in the grid"));
  deleteObject_ = button(tr("Delete"), QStringLiteral("deleteObject"), objectsBox);
  closeObject_ = button(tr("Close / Open (C)"), QStringLiteral("closeObject"), objectsBox);
  for (QPushButton* b : {newObject_, deleteObject_, closeObject_}) objectButtons->addWidget(b);
  objectsLayout->addLayout(objectButtons);
  layout->addWidget(objectsBox, 1);

  auto* cornersBox = new QGroupBox(tr("Corners of the selected object (tape measurements)"), this);
  auto* cornersLayout = new QVBoxLayout(cornersBox);
  auto* form = new QFormLayout;
  unit_ = new QComboBox(cornersBox);
  unit_->setObjectName(QStringLiteral("entryUnit"));
  for (LengthUnit u : kUnits) unit_->addItem(QString::fromLatin1(lengthUnitName(u)));
  unit_->setToolTip(tr("The unit you type in; the file keeps its own unit"));
  form->addRow(tr("&Unit:"), unit_);
  datum_ = new QComboBox(cornersBox);
  datum_->setObjectName(QStringLiteral("datum"));
  datum_->setToolTip(tr("Coordinates are offsets from this point (drawn as a red cross)"));
  form->addRow(tr("&Datum:"), datum_);
  cornersLayout->addLayout(form);
  corners_ = new QTableWidget(0, 2, cornersBox);
  corners_->setObjectName(QStringLiteral("corners"));
  corners_->setHorizontalHeaderLabels({tr("x"), tr("y")});
  corners_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  corners_->setSelectionBehavior(QAbstractItemView::SelectRows);
  corners_->setSelectionMode(QAbstractItemView::SingleSelection);
  cornersLayout->addWidget(corners_, 1);
  auto* cornerButtons = new QHBoxLayout;
  insertCorner_ = button(tr("Insert Before"), QStringLiteral("insertCorner"), cornersBox);
  insertCorner_->setToolTip(tr("A corner halfway along the edge into the selected corner"));
  deleteCorner_ = button(tr("Delete Corner (Del)"), QStringLiteral("deleteCorner"), cornersBox);
  cornerButtons->addWidget(insertCorner_);
  cornerButtons->addWidget(deleteCorner_);
  cornersLayout->addLayout(cornerButtons);
  auto* entry = new QHBoxLayout;
  entryX_ = new QLineEdit(cornersBox);
  entryX_->setObjectName(QStringLiteral("entryX"));
  entryX_->setPlaceholderText(tr("x"));
  entryY_ = new QLineEdit(cornersBox);
  entryY_->setObjectName(QStringLiteral("entryY"));
  entryY_->setPlaceholderText(tr("y"));
  addCorner_ = button(tr("&Add Corner"), QStringLiteral("addCorner"), cornersBox);
  entry->addWidget(entryX_);
  entry->addWidget(entryY_);
  entry->addWidget(addCorner_);
  cornersLayout->addLayout(entry);
  layout->addWidget(cornersBox, 2);
  message_ = new QLabel(this);
  message_->setObjectName(QStringLiteral("editorMessage"));
  message_->setWordWrap(true);
  layout->addWidget(message_);

  connect(model_, &ReferenceEditModel::changed, this, &ReferenceEditorPanel::refresh);
  connect(model_, &ReferenceEditModel::selectionChanged, this,
          &ReferenceEditorPanel::showSelection);
  connect(tool_, &ReferenceEditTool::message, this, &ReferenceEditorPanel::showMessage);
  connect(objects_, &QTableWidget::itemSelectionChanged, this, [this] {
    if (updating_) return;
    const auto rows = objects_->selectionModel()->selectedRows();
    model_->select(rows.isEmpty() ? -1 : rows.front().row());
  });
  connect(objects_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
    if (updating_) return;
    const int row = item->row();
    if (item->column() == 0) {
      if (!model_->renameObject(row, item->text().trimmed().toStdString()))
        showMessage(tr("Names must be unique and not empty"));
    } else if (item->column() == 1) {
      if (!model_->setClosed(row, item->checkState() == Qt::Checked))
        showMessage(tr("A closed object needs at least 3 corners"));
    }
    refresh(row);  // shows the model again when the edit was refused
  });
  connect(corners_, &QTableWidget::itemSelectionChanged, this, [this] {
    if (updating_) return;
    const auto rows = corners_->selectionModel()->selectedRows();
    model_->select(model_->selectedObject(), rows.isEmpty() ? -1 : rows.front().row());
  });
  connect(corners_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
    if (updating_) return;
    setTypedCoordinate(item->row(), item->column(), item->text());
    rebuildCorners();
  });
  connect(newObject_, &QPushButton::clicked, this, [this] {
    ReferenceObject o;
    o.name = model_->freeName();
    model_->addObject(std::move(o));
    entryX_->setFocus();
  });
  connect(deleteObject_, &QPushButton::clicked, this,
          [this] { model_->removeObject(model_->selectedObject()); });
  connect(closeObject_, &QPushButton::clicked, this, [this] {
    if (tool_->drawing()) return tool_->finishDrawing(true);
    if (const ReferenceObject* o = model_->object(model_->selectedObject()))
      if (!model_->setClosed(model_->selectedObject(), !o->closed))
        showMessage(tr("A closed object needs at least 3 corners"));
  });
  connect(deleteCorner_, &QPushButton::clicked, this,
          [this] { model_->removeCorner(model_->selectedObject(), model_->selectedCorner()); });
  connect(insertCorner_, &QPushButton::clicked, this, [this] {
    const ReferenceObject* o = model_->object(model_->selectedObject());
    const int c = model_->selectedCorner();
    if (!o || c < 0) return;
    const std::size_t n = o->corners.size();
    const std::size_t previous = (static_cast<std::size_t>(c) + n - 1) % n;
    model_->insertCorner(model_->selectedObject(), c,
                         (o->corners[previous] + o->corners[static_cast<std::size_t>(c)]) / 2.0);
  });
  connect(unit_, &QComboBox::currentIndexChanged, this, [this] { rebuildCorners(); });
  connect(datum_, &QComboBox::activated, this, [this](int index) {
    const QPoint d = datum_->itemData(index).toPoint();
    setDatum(d.x(), d.y());
  });
  connect(addCorner_, &QPushButton::clicked, this, [this] {
    if (addTypedCorner(entryX_->text(), entryY_->text())) {
      entryX_->clear();
      entryY_->clear();
      entryX_->setFocus();
    }
  });
  connect(entryX_, &QLineEdit::returnPressed, entryY_, qOverload<>(&QWidget::setFocus));
  connect(entryY_, &QLineEdit::returnPressed, addCorner_, &QPushButton::click);
  refresh(-1);
}

LengthUnit ReferenceEditorPanel::entryUnit() const {
  return kUnits[std::max(0, unit_->currentIndex())];
}

void ReferenceEditorPanel::setEntryUnit(LengthUnit unit) {
  for (int i = 0; i < 3; ++i)
    if (kUnits[i] == unit) unit_->setCurrentIndex(i);
}

void ReferenceEditorPanel::setDatum(int object, int corner) {
  const ReferenceObject* o = model_->object(object);
  if (!o || corner < 0 || corner >= static_cast<int>(o->corners.size())) object = corner = -1;
  datumObject_ = object;
  datumCorner_ = corner;
  datumName_ = o && object >= 0 ? o->name : std::string();
  tool_->setDatum(datumObject_, datumCorner_);
  rebuildDatums();
  rebuildCorners();
}

Eigen::Vector2d ReferenceEditorPanel::datumPosition() const {
  const ReferenceObject* o = model_->object(datumObject_);
  if (!o || datumCorner_ < 0 || datumCorner_ >= static_cast<int>(o->corners.size()))
    return Eigen::Vector2d::Zero();
  return o->corners[static_cast<std::size_t>(datumCorner_)];
}

void ReferenceEditorPanel::showMessage(const QString& text) {
  message_->setText(text);
}

bool ReferenceEditorPanel::addTypedCorner(const QString& x, const QString& y) {
  const LengthUnit stored = model_->map().unit;
  const auto dx = parseTypedLength(x, entryUnit(), stored);
  const auto dy = parseTypedLength(y, entryUnit(), stored);
  if (!dx || !dy) {
    showMessage(tr("Type x and y as numbers in %1, e.g. 123.5")
                    .arg(QString::fromLatin1(lengthUnitName(entryUnit()))));
    return false;
  }
  // The datum is the world origin, or a corner already in the map's unit: offsets add there, so
  // the sum is the same double whichever unit the offset was typed in.
  const Eigen::Vector2d corner = datumPosition() + Eigen::Vector2d(*dx, *dy);
  const int selected = model_->selectedObject();
  if (const ReferenceObject* o = model_->object(selected)) {
    model_->insertCorner(selected, static_cast<int>(o->corners.size()), corner);
  } else {
    ReferenceObject object;
    object.name = model_->freeName();
    object.corners.push_back(corner);
    model_->addObject(std::move(object));
    model_->select(model_->objectCount() - 1, 0);
  }
  showMessage({});
  return true;
}

bool ReferenceEditorPanel::setTypedCoordinate(int corner, int axis, const QString& text) {
  const int selected = model_->selectedObject();
  const ReferenceObject* o = model_->object(selected);
  if (!o || corner < 0 || corner >= static_cast<int>(o->corners.size())) return false;
  const auto v = parseTypedLength(text, entryUnit(), model_->map().unit);
  if (!v) {
    showMessage(tr("\"%1\" is not a number").arg(text));
    return false;
  }
  Eigen::Vector2d position = o->corners[static_cast<std::size_t>(corner)];
  position[axis] = datumPosition()[axis] + *v;
  model_->moveCorner(selected, corner, position);
  showMessage({});
  return true;
}

void ReferenceEditorPanel::refresh(int object) {
  // The datum follows its object by name (objects before it may come and go).
  if (!datumName_.empty()) {
    const int found = model_->findObject(datumName_);
    const ReferenceObject* o = model_->object(found);
    if (!o || datumCorner_ >= static_cast<int>(o->corners.size())) {
      datumName_.clear();
      datumObject_ = datumCorner_ = -1;
    } else {
      datumObject_ = found;
    }
    tool_->setDatum(datumObject_, datumCorner_);
  }
  if (object < 0) {
    const QString path = model_->path();
    fileLabel_->setText(
        !model_->hasReference()
            ? tr("No reference map: click corners in the grid or type them below.")
            : tr("<b>%1</b> — %2 objects, stored in %3")
                  .arg(path.isEmpty() ? tr("unsaved") : QFileInfo(path).fileName().toHtmlEscaped())
                  .arg(model_->objectCount())
                  .arg(QString::fromLatin1(lengthUnitName(model_->map().unit))));
  }
  rebuildObjects();
  rebuildDatums();
  rebuildCorners();
}

void ReferenceEditorPanel::rebuildObjects() {
  const bool was = updating_;
  updating_ = true;
  const ReferenceMap& map = model_->map();
  objects_->setRowCount(model_->objectCount());
  for (int i = 0; i < model_->objectCount(); ++i) {
    const ReferenceObject& o = map.objects[static_cast<std::size_t>(i)];
    cell(objects_, i, 0, kEditable)->setText(QString::fromStdString(o.name));
    cell(objects_, i, 1, kReadOnly | Qt::ItemIsUserCheckable)
        ->setCheckState(o.closed ? Qt::Checked : Qt::Unchecked);
    cell(objects_, i, 2, kReadOnly)->setText(QString::number(o.corners.size()));
  }
  updating_ = was;
  showSelection();
}

void ReferenceEditorPanel::rebuildDatums() {
  const QSignalBlocker block(datum_);
  datum_->clear();
  datum_->addItem(tr("world origin (0, 0)"), QPoint(-1, -1));
  const ReferenceMap& map = model_->map();
  for (int o = 0; o < model_->objectCount(); ++o) {
    const ReferenceObject& object = map.objects[static_cast<std::size_t>(o)];
    for (std::size_t c = 0; c < object.corners.size(); ++c) {
      datum_->addItem(tr("%1, corner %2").arg(QString::fromStdString(object.name)).arg(c + 1),
                      QPoint(o, static_cast<int>(c)));
      if (o == datumObject_ && static_cast<int>(c) == datumCorner_)
        datum_->setCurrentIndex(datum_->count() - 1);
    }
  }
}

void ReferenceEditorPanel::rebuildCorners() {
  const bool was = updating_;
  updating_ = true;
  const ReferenceObject* o = model_->object(model_->selectedObject());
  const LengthUnit stored = model_->map().unit;
  const Eigen::Vector2d datum = datumPosition();
  const int n = o ? static_cast<int>(o->corners.size()) : 0;
  corners_->setRowCount(n);
  for (int c = 0; c < n; ++c) {
    const Eigen::Vector2d offset = o->corners[static_cast<std::size_t>(c)] - datum;
    for (int axis = 0; axis < 2; ++axis) {
      // From the origin the stored number is shown as typed; an offset is a difference of
      // doubles, shown to 12 significant digits (far below a tape's millimetre).
      const QString text = datumObject_ < 0 ? typedLengthText(offset[axis], stored, entryUnit())
                                            : roundedLengthText(offset[axis], stored, entryUnit());
      cell(corners_, c, axis, kEditable)->setText(text);
    }
  }
  corners_->setHorizontalHeaderLabels(
      {tr("x (%1)").arg(QString::fromLatin1(lengthUnitName(entryUnit()))),
       tr("y (%1)").arg(QString::fromLatin1(lengthUnitName(entryUnit())))});
  if (model_->selectedCorner() >= 0 && model_->selectedCorner() < n)
    corners_->selectRow(model_->selectedCorner());
  const bool any = o != nullptr;
  deleteObject_->setEnabled(any);
  closeObject_->setEnabled(any || tool_->drawing());
  deleteCorner_->setEnabled(any && model_->selectedCorner() >= 0);
  insertCorner_->setEnabled(any && model_->selectedCorner() >= 0 && n >= 2);
  updating_ = was;
}

void ReferenceEditorPanel::showSelection() {
  const bool was = updating_;
  updating_ = true;
  const int selected = model_->selectedObject();
  if (selected >= 0)
    objects_->selectRow(selected);
  else
    objects_->clearSelection();
  updating_ = was;
  rebuildCorners();
}

}  // namespace sg::ui
