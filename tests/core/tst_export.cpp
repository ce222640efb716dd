#include <QtTest>
class Tstexport : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstexport)
#include "tst_export.moc"
