#include <QtTest>
class Tstmodels : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstmodels)
#include "tst_models.moc"
