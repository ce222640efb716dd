#include <QtTest>
class Tstroom_dataset : public QObject {
  Q_OBJECT
};
QTEST_GUILESS_MAIN(Tstroom_dataset)
#include "tst_room_dataset.moc"
