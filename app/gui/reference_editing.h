// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The reference editor's place in the window: an undo stack (held by the window until the
// Document owns it), an Edit menu (Undo, Redo and the editor's actions) and the editor's dock.

class QMainWindow;

namespace sg::ui {
class GridView;
class ReferenceEditor;
}  // namespace sg::ui

namespace sg::app {

// Creates them as children of `window`; returns the editor (owned by `window`).
ui::ReferenceEditor* installReferenceEditor(QMainWindow* window, ui::GridView* view);

}  // namespace sg::app
