// SPDX-License-Identifier: GPL-3.0-or-later
// The GUI's files (view PNG and SVG, screenshots) go through the core's atomic writer: the encoded
// bytes arrive whole, no temporary file is left, and a failure names the path.

#include <QBuffer>
#include <QDir>
#include <QFile>
#include <QImage>
#include <QPainter>
#include <QSvgGenerator>
#include <QTemporaryDir>
#include <QtTest>

#include "export_file.h"

class TstExportFile : public QObject {
  Q_OBJECT

 private slots:
  void pngRoundTrip() {
    QImage image(3, 2, QImage::Format_RGB32);
    const QRgb colours[6] = {qRgb(246, 249, 255), qRgb(223, 234, 255), qRgb(197, 219, 255),
                             qRgb(120, 25, 19),   qRgb(133, 115, 110), qRgb(0, 0, 0)};
    for (int i = 0; i < 6; ++i) image.setPixel(i % 3, i / 3, colours[i]);
    const QByteArray png = sg::app::encodedImage(image, "PNG");
    QVERIFY(png.startsWith("\x89PNG\r\n\x1a\n"));

    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath("view.png");
    QCOMPARE(sg::app::writeFileBytes(path, png), QString());
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QCOMPARE(file.readAll(), png);
    // PNG is lossless: the same pixels come back.
    QCOMPARE(QImage(path).convertToFormat(QImage::Format_RGB32), image);
    QCOMPARE(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"view.png"});
  }

  void svgThroughMemory() {
    // The view's SVG export: QSvgGenerator draws into a buffer, the bytes go to the atomic writer.
    QByteArray bytes;
    QBuffer buffer(&bytes);
    QVERIFY(buffer.open(QIODevice::WriteOnly));
    QSvgGenerator svg;
    svg.setOutputDevice(&buffer);
    svg.setSize(QSize(40, 30));
    svg.setViewBox(QRect(0, 0, 40, 30));
    QPainter painter;
    QVERIFY(painter.begin(&svg));
    painter.drawLine(0, 0, 40, 30);
    painter.end();
    QVERIFY(bytes.contains("<svg") && bytes.trimmed().endsWith("</svg>"));

    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath("view.svg");
    QCOMPARE(sg::app::writeFileBytes(path, bytes), QString());
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QCOMPARE(file.readAll(), bytes);
    QCOMPARE(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"view.svg"});
  }

  void unknownFormatGivesNoBytes() {
    QImage image(2, 2, QImage::Format_RGB32);
    image.fill(Qt::white);
    QVERIFY(sg::app::encodedImage(image, "no-such-format").isEmpty());
  }

  void failureNamesThePath() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString path = dir.filePath("missing/view.svg");
    QCOMPARE(sg::app::writeFileBytes(path, QByteArray("<svg/>")),
             QStringLiteral("cannot write '%1': directory '%2' does not exist")
                 .arg(path, dir.filePath("missing")));
    QVERIFY(QDir(dir.path()).isEmpty());
  }
};

QTEST_MAIN(TstExportFile)
#include "tst_export_file.moc"
