// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Help menu's windows: the user guide (docs/user-guide.md, built into the app), the keyboard
// shortcuts read from the window's menus (so the list cannot go stale) and About.

class QMainWindow;
class QWidget;

namespace sg::app {

void showUserGuide(QWidget* parent);
void showShortcuts(QMainWindow* window);
void showAbout(QWidget* parent);

}  // namespace sg::app
