#include <QtTest>
class Tstgeometry : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstgeometry)
#include "tst_geometry.moc"
