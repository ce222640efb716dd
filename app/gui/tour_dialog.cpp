// SPDX-License-Identifier: GPL-3.0-or-later
#include "tour_dialog.h"

#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>

#include "beam_model_view.h"
#include "datasets_location.h"
#include "document.h"
#include "main_window.h"
#include "parameter_panel.h"
#include "reference_editor.h"
#include "sonargrid/params/presets.h"

namespace sg::app {
namespace {

// The settings of a paper preset, keeping the window's pose source.
void usePreset(MainWindow& w, const char* name) {
  const Preset* preset = findPreset(name);
  if (!preset) return;
  MapperSettings s = applyPreset(*preset);
  s.pose = w.mapperSettings().pose;
  w.setMapperSettings(s, /*ruleNamed=*/true);  // a preset names its rule
}

// The reference map as step 1 describes it: drawn (the Reference overlay on) and not in edit mode,
// where the editor draws it blue with corner handles.
void showReference(MainWindow& w) {
  Document& d = *w.document();
  if (!d.overlays().testFlag(ui::Overlay::Reference))
    d.setOverlays(d.overlays() | ui::Overlay::Reference);
  if (auto* editor = w.findChild<ui::ReferenceEditor*>())
    if (editor->editModeAction()->isChecked()) editor->editModeAction()->trigger();
}

// Arafat et al.'s parameterized model at Table 1's minimum-VSDNS set (P3 = 0.25 m, P5 = 6°) with
// P5 = `p5`. Figure 6's set has P3 = 1.0 in the sensor's range units (feet in Murphy's examples),
// which as metres draws a 2 m occupied band around every echo: no wall shows (issue 49).
void useParameterized(MainWindow& w, double p5) {
  usePreset(w, "paper002-table1-min-vsdns");
  MapperSettings s = w.mapperSettings();
  s.parameters.set("p5", p5);
  w.setMapperSettings(s);
}

void raiseDock(MainWindow& w, const char* objectName) {
  if (auto* dock = w.findChild<QDockWidget*>(QLatin1String(objectName))) {
    dock->show();
    dock->raise();
  }
}

}  // namespace

TourDialog::TourDialog(MainWindow* window)
    : QDialog(window),
      window_(window),
      heading_(new QLabel(this)),
      body_(new QLabel(this)),
      counter_(new QLabel(this)),
      back_(new QPushButton(tr("< &Back"), this)),
      next_(new QPushButton(tr("&Next >"), this)) {
  setWindowTitle(tr("Sonar Models in 5 Minutes"));
  setModal(false);
  const QString log =
      QDir(bundledDatasetsDirectory()).filePath(QStringLiteral("raschke-multi/in-motion-01.sglog"));
  steps_ = {
      {tr("A room and its map"),
       tr("This is run 1 of the obstacle course of Raschke & Borenstein (1990): a robot with 24 "
          "sonars drives among boxes, partitions and a thin pole. The green lines are the room as "
          "it really is (the reference map); the coloured cells are what the sonars made of it. "
          "White to blue is free, dark red occupied, khaki never observed."),
       [log](MainWindow& w) {
         if (QFileInfo::exists(log) && w.logPath() != log) w.openLog(log);
         usePreset(w, "paper000-himm");
         showReference(w);
       }},
      {tr("HIMM: one cell per echo"),
       tr("The map is built with HIMM, the histogram method: each echo adds 3 to the one cell on "
          "the beam's axis at the measured range and takes 1 from the cells before it. Walls come "
          "out thin and sharp, because only the axis is written."),
       [](MainWindow& w) { usePreset(w, "paper000-himm"); }},
      {tr("HPF: the whole cone"),
       tr("Now the same log with HPF, the Moravec–Elfes probability functions: every echo spreads "
          "evidence over the whole 25° cone, occupied along an arc at the range and free inside "
          "it. Walls are thicker and blurred — the difference the 1990 paper measured with its "
          "Index of Performance. Use Back and Next to flip between the two."),
       [](MainWindow& w) { usePreset(w, "paper000-hpf"); }},
      {tr("The beam view's regions"),
       tr("The Beam Model dock draws what one reading writes. With the parameterized model of "
          "Arafat et al. it shows Region I around the range s (occupied), Region II before it "
          "(free) and Region III beyond it (no update). The top picture is the cone seen from "
          "above, the middle one the values along the axis. Its cone is 15° wide on each side of "
          "the axis, as in the paper's Figure 6."),
       [](MainWindow& w) {
         useParameterized(w, 15.0);
         raiseDock(w, "beamModelDock");
       }},
      {tr("One slider: the beam's width"),
       tr("P5 is half the beam's width. The paper's Figure 6 uses 15°; the set of its Table 1 with "
          "the lowest VSDNS uses 6°. The tour has set P5 to 6°: the cone in the beam view narrows, "
          "the occupied arcs thin and the map's walls sharpen (its Index of Performance falls). "
          "Drag the P5 slider in the Parameters dock yourself and watch both."),
       [](MainWindow& w) {
         useParameterized(w, 6.0);
         raiseDock(w, "parametersDock");
         raiseDock(w, "beamModelDock");
         if (QSlider* slider = w.parameterPanel()->sliderFor(QStringLiteral("p5")))
           slider->setFocus();
       }},
      {tr("Your turn"),
       tr("Every change of model or parameter can be undone (Edit ▸ Undo). File ▸ Open Example "
          "opens the other datasets; "
          "the Paper presets in the Parameters dock set each paper's values; Help ▸ User Guide "
          "explains the rest."),
       [](MainWindow&) {}},
  };

  heading_->setObjectName(QStringLiteral("tourHeading"));
  QFont bold = heading_->font();
  bold.setBold(true);
  bold.setPointSizeF(bold.pointSizeF() * 1.2);
  heading_->setFont(bold);
  body_->setObjectName(QStringLiteral("tourText"));
  body_->setWordWrap(true);
  body_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  body_->setMinimumHeight(120);
  back_->setObjectName(QStringLiteral("tourBack"));
  next_->setObjectName(QStringLiteral("tourNext"));
  auto* close = new QPushButton(tr("&Close"), this);
  connect(back_, &QPushButton::clicked, this, &TourDialog::back);
  connect(next_, &QPushButton::clicked, this, &TourDialog::next);
  connect(close, &QPushButton::clicked, this, &QDialog::close);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(counter_);
  buttons->addStretch(1);
  buttons->addWidget(back_);
  buttons->addWidget(next_);
  buttons->addWidget(close);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(heading_);
  layout->addWidget(body_, 1);
  layout->addLayout(buttons);
  resize(460, 260);
  showStep(0);
}

QString TourDialog::stepTitle() const {
  return step_ >= 0 ? steps_[static_cast<std::size_t>(step_)].title : QString();
}

void TourDialog::showStep(int index) {
  index = std::clamp(index, 0, stepCount() - 1);
  if (index == step_) return;
  step_ = index;
  const Step& s = steps_[static_cast<std::size_t>(index)];
  heading_->setText(s.title);
  body_->setText(s.text);
  counter_->setText(tr("Step %1 of %2").arg(index + 1).arg(stepCount()));
  back_->setEnabled(index > 0);
  next_->setEnabled(index + 1 < stepCount());
  if (s.apply) s.apply(*window_);
}

}  // namespace sg::app
