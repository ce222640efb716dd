#include <QtTest>
class Tstsglog : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstsglog)
#include "tst_sglog.moc"
