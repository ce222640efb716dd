// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The reference editor's dock: the objects (rename, delete, open or closed) and the corner table
// where tape-measured coordinates are typed. Coordinates are typed in the unit chosen (m, cm, mm)
// as offsets from a datum (the world origin or any corner), as a survey with a tape is written
// down: "the absolute coordinates of the corners comprising each object are measured" (paper 000
// §3), in practice from one corner of the room. Typed numbers convert to the map's own unit as
// decimals (typed_length.h), so typing in cm gives the same reference as typing in m.

#include <Eigen/Core>
#include <QWidget>
#include <string>

#include "sonargrid/base/length_unit.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTableWidget;

namespace sg::ui {

class ReferenceEditModel;
class ReferenceEditTool;

class ReferenceEditorPanel : public QWidget {
  Q_OBJECT

 public:
  ReferenceEditorPanel(ReferenceEditModel* model, ReferenceEditTool* tool,
                       QWidget* parent = nullptr);

  LengthUnit entryUnit() const;
  void setEntryUnit(LengthUnit unit);
  // The datum: object -1 is the world origin.
  void setDatum(int object, int corner);
  int datumObject() const { return datumObject_; }
  int datumCorner() const { return datumCorner_; }
  // Appends a corner typed as offsets (in the entry unit, from the datum) to the selected object,
  // or starts a new object with it when none is selected. False (and a message) on bad text.
  bool addTypedCorner(const QString& x, const QString& y);
  // Sets coordinate `axis` (0 x, 1 y) of corner `corner` of the selected object from typed text.
  bool setTypedCoordinate(int corner, int axis, const QString& text);

  // The file buttons, wired by the ReferenceEditor.
  QPushButton* newButton() const { return newButton_; }
  QPushButton* openButton() const { return openButton_; }
  QPushButton* saveButton() const { return saveButton_; }
  QPushButton* saveAsButton() const { return saveAsButton_; }
  void showMessage(const QString& text);

 private:
  void rebuildObjects();
  void rebuildCorners();
  void rebuildDatums();
  void refresh(int object);
  void showSelection();
  Eigen::Vector2d datumPosition() const;

  ReferenceEditModel* model_;
  ReferenceEditTool* tool_;
  QLabel* fileLabel_;
  QPushButton *newButton_, *openButton_, *saveButton_, *saveAsButton_;
  QCheckBox* snap_;
  QTableWidget* objects_;
  QPushButton *newObject_, *deleteObject_, *closeObject_;
  QComboBox* unit_;
  QComboBox* datum_;
  QTableWidget* corners_;
  QPushButton *deleteCorner_, *insertCorner_;
  QLineEdit *entryX_, *entryY_;
  QPushButton* addCorner_;
  QLabel* message_;
  int datumObject_ = -1;
  int datumCorner_ = -1;
  std::string datumName_;  // the datum follows its object by name through edits
  bool updating_ = false;
};

}  // namespace sg::ui
