// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view's place in the app (docs/user-guide.md, "Sweeping parameters"): its window, its
// menu entry, and its link with the Document: the document's logs, reference, settings and cell
// size feed the view; the view's choice is the document's sweep settings (saved with the project,
// undoable); applying a set is one undoable settings edit (which re-maps); pinning adds a row to
// the comparison table (Document::pinRow).

namespace sg::ui {
class SweepView;
}  // namespace sg::ui

namespace sg::app {

class Document;
class MainWindow;

// Connects `view` and `document` both ways (as above) and shows the document's state in it.
void connectSweepView(ui::SweepView* view, Document* document);

// Creates the sweep view as a window of its own, owned by `window` (closing the app mid-sweep
// cancels it), connected to the window's Document, with Mapping ▸ Sweep Parameters… (Ctrl+Shift+W)
// showing it. Returns it.
ui::SweepView* installSweepView(MainWindow* window);

}  // namespace sg::app
