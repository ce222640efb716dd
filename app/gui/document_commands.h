// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Document's undo commands, one per kind of edit (as Tiled's changepolygon.h). Each holds the
// value before and after; steps of one drag share a drag id and merge into one command
// (QUndoCommand::id / mergeWith), so a slider dragged across its range is one undo step.

#include <QUndoCommand>
#include <optional>
#include <vector>

#include "project.h"

namespace sg::app {

class Document;

enum class CommandId { Settings = 1, CellSize, Reference, PinnedRows, Sweep };

class SetSettingsCommand : public QUndoCommand {
 public:
  SetSettingsCommand(Document* document, MapperSettings before, MapperSettings after, quint64 drag);
  void undo() override;
  void redo() override;
  int id() const override { return static_cast<int>(CommandId::Settings); }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  MapperSettings before_, after_;
  quint64 drag_;
};

class SetCellSizeCommand : public QUndoCommand {
 public:
  SetCellSizeCommand(Document* document, double before, double after, quint64 drag);
  void undo() override;
  void redo() override;
  int id() const override { return static_cast<int>(CommandId::CellSize); }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  double before_, after_;
  quint64 drag_;
};

struct ReferenceValue {
  std::optional<ReferenceMap> map;
  QString path;
  bool modified = false;
};

class SetReferenceCommand : public QUndoCommand {
 public:
  SetReferenceCommand(Document* document, ReferenceValue before, ReferenceValue after,
                      const QString& text);
  void undo() override;
  void redo() override;

 private:
  Document* document_;
  ReferenceValue before_, after_;
};

class SetPinnedRowsCommand : public QUndoCommand {
 public:
  SetPinnedRowsCommand(Document* document, std::vector<PinnedRow> before,
                       std::vector<PinnedRow> after, const QString& text);
  void undo() override;
  void redo() override;

 private:
  Document* document_;
  std::vector<PinnedRow> before_, after_;
};

class SetStartPoseCommand : public QUndoCommand {
 public:
  SetStartPoseCommand(Document* document, std::optional<Pose2D> before,
                      std::optional<Pose2D> after);
  void undo() override;
  void redo() override;

 private:
  Document* document_;
  std::optional<Pose2D> before_, after_;
};

class SetSweepCommand : public QUndoCommand {
 public:
  SetSweepCommand(Document* document, SweepPlan before, SweepPlan after);
  void undo() override;
  void redo() override;

 private:
  Document* document_;
  SweepPlan before_, after_;
};

}  // namespace sg::app
