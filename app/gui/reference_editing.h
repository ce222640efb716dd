// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The reference editor's place in the window: its actions in the Edit menu, its dock, and the
// two-way link with the Document, whose undo stack takes the editor's steps.

namespace sg::ui {
class ReferenceEditor;
}  // namespace sg::ui

namespace sg::app {

class MainWindow;

// Creates the editor as a child of `window`, on the window's Document; returns it.
ui::ReferenceEditor* installReferenceEditor(MainWindow* window);

}  // namespace sg::app
