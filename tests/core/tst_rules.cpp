#include <QtTest>
class Tstrules : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstrules)
#include "tst_rules.moc"
