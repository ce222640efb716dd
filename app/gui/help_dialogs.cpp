// SPDX-License-Identifier: GPL-3.0-or-later
#include "help_dialogs.h"

#include <QAction>
#include <QApplication>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFile>
#include <QHeaderView>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QTableWidget>
#include <QTextBrowser>
#include <QVBoxLayout>

namespace sg::app {

void showUserGuide(QWidget* parent) {
  QFile file(QStringLiteral(":/sonargrid/user-guide.md"));
  file.open(QIODevice::ReadOnly);
  auto* dialog = new QDialog(parent);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->setWindowTitle(QObject::tr("SonarGrid User Guide"));
  auto* text = new QTextBrowser(dialog);
  text->setOpenExternalLinks(true);
  text->setMarkdown(QString::fromUtf8(file.readAll()));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(text);
  layout->addWidget(buttons);
  dialog->resize(720, 640);
  dialog->show();
}

void showShortcuts(QMainWindow* window) {
  // Every menu action with a shortcut, read from the menus so that the list cannot go stale, then
  // the keys and gestures the grid view handles itself.
  QList<QPair<QString, QString>> rows;
  for (QAction* menu : window->menuBar()->actions()) {
    if (!menu->menu()) continue;
    for (QAction* a : menu->menu()->actions())
      if (!a->shortcut().isEmpty())
        rows.append({a->text().remove('&'), a->shortcut().toString(QKeySequence::NativeText)});
  }
  rows.append({QObject::tr("Zoom in / out"), QObject::tr("+ / −, mouse wheel, pinch")});
  rows.append({QObject::tr("Pan"), QObject::tr("arrow keys, drag with the left or middle button")});
  rows.append({QObject::tr("Fit to map"), QObject::tr("F, Home, double-click")});
  rows.append(
      {QObject::tr("Move a parameter slider"), QObject::tr("arrows, Page Up / Down, Home / End")});
  auto* dialog = new QDialog(window);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->setWindowTitle(QObject::tr("Keyboard Shortcuts"));
  auto* table = new QTableWidget(static_cast<int>(rows.size()), 2, dialog);
  table->setHorizontalHeaderLabels({QObject::tr("Action"), QObject::tr("Keys")});
  table->verticalHeader()->hide();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int i = 0; i < rows.size(); ++i) {
    table->setItem(i, 0, new QTableWidgetItem(rows[i].first));
    table->setItem(i, 1, new QTableWidgetItem(rows[i].second));
  }
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(table);
  layout->addWidget(buttons);
  dialog->resize(520, 560);
  dialog->show();
}

void showAbout(QWidget* parent) {
  QMessageBox::about(
      parent, QObject::tr("About SonarGrid"),
      QObject::tr(
          "<b>SonarGrid %1</b><p>A workbench for sonar occupancy-grid mapping: five inverse sensor "
          "models, seven update rules, 16 certainty levels.</p>")
          .arg(QApplication::applicationVersion()));
}

}  // namespace sg::app
