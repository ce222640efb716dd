// SPDX-License-Identifier: GPL-3.0-or-later
// The Mapping threads preference (app/gui/preferences.h): its typed QSettings key, how it reaches
// the core's thread policy at start and from the Preferences dialog, and the dialog behind
// Settings ▸ Preferences in the window.

#include <QApplication>
#include <QCheckBox>
#include <QMenuBar>
#include <QSettings>
#include <QSpinBox>
#include <QStandardPaths>
#include <QTimer>
#include <QtTest>
#include <functional>

#include "main_window.h"
#include "preferences.h"
#include "remap_controller.h"
#include "sonargrid/base/concurrency.h"

using namespace sg;

class TestPreferences : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_preferences");
  }
  void init() {
    QSettings().clear();
    qunsetenv(kThreadsVariable);
    setThreadCount(0);
  }
  void cleanup() { setThreadCount(0); }

  void storedValueReachesThePolicy_data() {
    QTest::addColumn<QVariant>("stored");  // invalid: never stored
    QTest::addColumn<int>("expected");     // 0: automatic
    QTest::newRow("never set: automatic") << QVariant() << 0;
    QTest::newRow("0: automatic") << QVariant(0) << 0;
    QTest::newRow("3") << QVariant(3) << 3;
    QTest::newRow("more than the CPUs") << QVariant(16) << 16;
    // A settings file edited by hand: out of range or not a number count as automatic.
    QTest::newRow("negative") << QVariant(-4) << 0;
    QTest::newRow("above the maximum") << QVariant(5000) << 0;
    QTest::newRow("a word") << QVariant(QStringLiteral("many")) << 0;
  }
  void storedValueReachesThePolicy() {
    QFETCH(QVariant, stored);
    QFETCH(int, expected);
    if (stored.isValid()) QSettings().setValue(app::preferences::kMappingThreads.key(), stored);
    const unsigned inForce = app::applyMappingThreads();
    QCOMPARE(explicitThreadCount(), static_cast<unsigned>(expected));
    QCOMPARE(inForce, expected == 0 ? automaticThreadCount() : static_cast<unsigned>(expected));
    QCOMPARE(threadCount(), inForce);
  }

  void automaticNamesItsSource() {
    QVERIFY(app::automaticThreadsDescription().contains(QString::number(affinityThreadCount())));
    qputenv(kThreadsVariable, "5");
    QVERIFY(app::automaticThreadsDescription().startsWith("5, from the environment variable"));
    qputenv(kThreadsVariable, "five");
    // A bad value is said, with the count used instead.
    const QString bad = app::automaticThreadsDescription();
    QVERIFY2(bad.contains("'five'") && bad.contains("ignored"), qPrintable(bad));
    qunsetenv(kThreadsVariable);
  }

  void dialogStoresAndApplies() {
    app::preferences::kMappingThreads.set(2);
    app::PreferencesDialog dialog;
    QSpinBox* spin = dialog.mappingThreads();
    QCOMPARE(spin->value(), 2);
    spin->setValue(0);  // shown as "Automatic (N)"
    QCOMPARE(spin->text(), QStringLiteral("Automatic (%1)").arg(automaticThreadCount()));
    spin->setValue(3);
    dialog.accept();
    QCOMPARE(QSettings().value(app::preferences::kMappingThreads.key()).toInt(), 3);
    QCOMPARE(threadCount(), 3u);

    app::PreferencesDialog cancelled;
    cancelled.mappingThreads()->setValue(7);
    cancelled.reject();
    QCOMPARE(app::preferences::kMappingThreads.value(), 3);
    QCOMPARE(threadCount(), 3u);
  }

  void windowOpensItFromTheSettingsMenu() {
    app::MainWindow window(ui::GridView::Backend::Raster);
    QAction* action = nullptr;
    for (QAction* menu : window.menuBar()->actions()) {
      if (menu->text().remove('&') != "Settings" || !menu->menu()) continue;
      for (QAction* a : menu->menu()->actions())
        if (a->text().remove('&').startsWith("Preferences")) action = a;
    }
    QVERIFY(action);
    bool shown = false;
    int tries = 0;
    std::function<void()> answer = [&] {
      auto* dialog = qobject_cast<app::PreferencesDialog*>(QApplication::activeModalWidget());
      if (!dialog) {
        if (++tries < 500) QTimer::singleShot(10, this, answer);  // not up yet
        return;
      }
      shown = true;
      dialog->mappingThreads()->setValue(4);
      QVERIFY(!dialog->fastEngine()->isChecked());  // the exact engine by default
      dialog->fastEngine()->setChecked(true);
      dialog->accept();
    };
    QCOMPARE(window.remapController()->precision(), Precision::Exact);
    QTimer::singleShot(0, this, answer);
    action->trigger();  // the dialog is modal: returns once the timer has accepted it
    QVERIFY(shown);
    QCOMPARE(app::preferences::kMappingThreads.value(), 4);
    QCOMPARE(threadCount(), 4u);
    // The engine reaches the window's re-maps, and a new window starts with it.
    QVERIFY(app::preferences::kFastEngine.value());
    QCOMPARE(window.remapController()->precision(), Precision::Fast);
    app::MainWindow next(ui::GridView::Backend::Raster);
    QCOMPARE(next.remapController()->precision(), Precision::Fast);
  }
};

QTEST_MAIN(TestPreferences)
#include "tst_preferences.moc"
