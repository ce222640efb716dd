#include <QtTest>
class Tstmapper : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstmapper)
#include "tst_mapper.moc"
