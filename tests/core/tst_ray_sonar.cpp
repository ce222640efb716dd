#include <QtTest>
class Tstray_sonar : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstray_sonar)
#include "tst_ray_sonar.moc"
