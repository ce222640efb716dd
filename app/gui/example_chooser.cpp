// SPDX-License-Identifier: GPL-3.0-or-later
#include "example_chooser.h"

#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QIcon>
#include <QLabel>
#include <QListWidget>
#include <QPainter>
#include <QPixmap>
#include <QPushButton>
#include <QVBoxLayout>
#include <algorithm>
#include <limits>

#include "grid_image.h"
#include "sonargrid/reference/read_reference.h"

namespace sg::app {

QImage ExampleChooser::thumbnail(const DatasetManifest& dataset, QSize size) {
  QImage image(size, QImage::Format_RGB32);
  image.fill(Qt::white);
  if (!dataset.thumbnail.isEmpty()) {
    const QImage picture(dataset.thumbnail);
    if (!picture.isNull()) {
      QPainter p(&image);
      const QImage scaled = picture.scaled(size, Qt::KeepAspectRatio, Qt::SmoothTransformation);
      p.drawImage((size.width() - scaled.width()) / 2, (size.height() - scaled.height()) / 2,
                  scaled);
      return image;
    }
  }
  if (dataset.reference.isEmpty()) return image;
  std::vector<std::vector<Position>> lines;
  try {
    lines = ui::referencePolylines(
        readReference(QDir::toNativeSeparators(dataset.reference).toStdString()));
  } catch (const std::exception&) {
    return image;  // the reference's own error shows when the log is opened
  }
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto& line : lines)
    for (const Position& p : line) {
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
  if (!(x1 > x0) || !(y1 > y0)) return image;
  constexpr int kMargin = 4;
  const double scale =
      std::min((size.width() - 2 * kMargin) / (x1 - x0), (size.height() - 2 * kMargin) / (y1 - y0));
  const double left = (size.width() - scale * (x1 - x0)) / 2.0;
  const double top = (size.height() - scale * (y1 - y0)) / 2.0;
  QPainter p(&image);
  p.setRenderHint(QPainter::Antialiasing);
  p.setPen(QPen(QColor(30, 30, 30), 1.5));
  for (const auto& line : lines) {
    QPolygonF poly;
    for (const Position& q : line)
      poly << QPointF(left + (q.x() - x0) * scale, top + (y1 - q.y()) * scale);  // north up
    p.drawPolyline(poly);
  }
  return image;
}

ExampleChooser::ExampleChooser(std::vector<DatasetManifest> datasets, QWidget* parent)
    : QDialog(parent), datasets_(std::move(datasets)), list_(new QListWidget(this)) {
  setWindowTitle(tr("Open Example"));
  const QSize thumb(120, 80);
  list_->setObjectName(QStringLiteral("exampleList"));
  list_->setIconSize(thumb);
  list_->setWordWrap(true);
  list_->setSpacing(4);
  list_->setUniformItemSizes(false);
  for (const DatasetManifest& d : datasets_) {
    auto* item = new QListWidgetItem(QIcon(QPixmap::fromImage(thumbnail(d, thumb))),
                                     d.title + QLatin1Char('\n') + d.description, list_);
    item->setToolTip(tr("%1 — opens %2 with its reference map")
                         .arg(QDir::toNativeSeparators(d.folder), QFileInfo(d.example).fileName()));
    item->setData(Qt::UserRole, d.name);
  }
  if (list_->count() > 0) list_->setCurrentRow(0);

  auto* intro = new QLabel(
      tr("The bundled datasets, each with its reference map. Open maps the dataset's first "
         "run; Other run… picks another log of the same dataset."),
      this);
  intro->setWordWrap(true);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Open | QDialogButtonBox::Cancel, this);
  QPushButton* other = buttons->addButton(tr("Other &run…"), QDialogButtonBox::ActionRole);
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    const int row = list_->currentRow();
    if (row < 0) return;
    chosen_ = datasets_[static_cast<std::size_t>(row)].example;
    accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(other, &QPushButton::clicked, this, &ExampleChooser::openOther);
  connect(list_, &QListWidget::itemActivated, buttons, &QDialogButtonBox::accepted);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(intro);
  layout->addWidget(list_, 1);
  layout->addWidget(buttons);
  resize(640, 520);
}

bool ExampleChooser::choose(const QString& name) {
  for (int i = 0; i < list_->count(); ++i)
    if (list_->item(i)->data(Qt::UserRole).toString() == name) {
      list_->setCurrentRow(i);
      chosen_ = datasets_[static_cast<std::size_t>(i)].example;
      accept();
      return true;
    }
  return false;
}

void ExampleChooser::openOther() {
  const int row = list_->currentRow();
  if (row < 0) return;
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open a Run"), datasets_[std::size_t(row)].folder, tr("SonarGrid logs (*.sglog)"));
  if (path.isEmpty()) return;
  chosen_ = path;
  accept();
}

}  // namespace sg::app
