// SPDX-License-Identifier: GPL-3.0-or-later
// Slider-change -> repainted-view latency (issue 5, item 10). Not run by ctest.
//
//   bench_remap_latency LOG [--model M] [--rule R] [--param NAME] [--steps N] [--pose odom|truth]
//                       [--cell METRES] [--controller] [--probe N] [--reference REF] [--metrics]
//
// By default it opens LOG in the app's MainWindow (parameter panel, beam view and all), sets the
// panel's slider of NAME (default: the model's first parameter) to N positions across its range
// (default 40), one at a time, and reports the median and p95 of the time from setting the slider
// to the first repaint of the grid view showing the full map of that value, and to the first
// repaint showing that value at all (the window previews a slow log's change on coarser cells).
// --controller drives a bare RemapController + GridView instead (no panel, no window), to tell the
// GUI's share apart.
//
// --metrics (window only) also waits, at each step, for the metrics panel to show the numbers of
// that step's full map (IOP and the rest with --reference REF, goodness without), and reports the
// time from the change to the panel's refresh and the panel's own computation time.
//
// --probe N then re-maps N more times (default 0) while a 16 ms timer on the GUI thread (1) records
// how late it fires, (2) posts a mouse move over the grid view and times it until the hover
// read-out changes, and (3) every fourth tick posts an arrow key (a pan) and times it until the
// view has repainted: the view stays interactive while re-mapping when those stay within a frame or
// two. The same probes over an idle second give the baseline of the (possibly loaded) machine.
//
// Run it under xvfb-run for the OpenGL surface, or with QT_QPA_PLATFORM=offscreen for the raster
// one.

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QSlider>
#include <QStandardPaths>
#include <QTimer>
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>

#include "grid_view.h"
#include "main_window.h"
#include "metrics_panel.h"
#include "parameter_panel.h"
#include "remap_controller.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/sglog.h"

namespace {

struct Summary {
  double median = 0.0, p95 = 0.0, max = 0.0;
  std::size_t count = 0;
};

Summary summarise(std::vector<double> ms) {
  Summary s;
  s.count = ms.size();
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  auto quantile = [&](double q) {
    return ms[static_cast<std::size_t>(std::ceil(q * static_cast<double>(ms.size())) - 1)];
  };
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  s.max = ms.back();
  return s;
}

std::ostream& operator<<(std::ostream& out, const Summary& s) {
  return out << "median " << s.median << " ms, p95 " << s.p95 << " ms, max " << s.max << " ms (n "
             << s.count << ")";
}

// The 16 ms timer's lateness and the hover and pan round trips, while `busy` holds.
struct Probes {
  std::vector<double> timerLate, hover, pan;
};

Probes probe(sg::ui::GridView& view, const std::function<bool()>& busy) {
  Probes out;
  QTimer timer;
  timer.setTimerType(Qt::PreciseTimer);
  timer.setInterval(16);
  QElapsedTimer clock;
  clock.start();
  qint64 lastTick = clock.nsecsElapsed();
  qint64 hoverPosted = -1, panPosted = -1;
  int tick = 0;
  const auto onHover = QObject::connect(&view, &sg::ui::GridView::hoverText, [&] {
    if (hoverPosted < 0) return;
    out.hover.push_back(static_cast<double>(clock.nsecsElapsed() - hoverPosted) * 1e-6);
    hoverPosted = -1;
  });
  const auto onPaint = QObject::connect(&view, &sg::ui::GridView::repainted, [&] {
    if (panPosted < 0) return;
    out.pan.push_back(static_cast<double>(clock.nsecsElapsed() - panPosted) * 1e-6);
    panPosted = -1;
  });
  QObject::connect(&timer, &QTimer::timeout, [&] {
    const qint64 now = clock.nsecsElapsed();
    out.timerLate.push_back(std::max(0.0, static_cast<double>(now - lastTick) * 1e-6 - 16.0));
    lastTick = now;
    ++tick;
    const QPointF at(view.width() * (0.3 + 0.4 * (tick % 7) / 7.0), view.height() * 0.5);
    if (hoverPosted < 0) {
      hoverPosted = now;
      QCoreApplication::postEvent(
          &view, new QMouseEvent(QEvent::MouseMove, at, view.mapToGlobal(at), Qt::NoButton,
                                 Qt::NoButton, Qt::NoModifier));
    }
    if (tick % 4 == 0 && panPosted < 0) {
      panPosted = now;
      const int key = (tick / 4) % 2 ? Qt::Key_Left : Qt::Key_Right;  // back and forth
      QCoreApplication::postEvent(&view, new QKeyEvent(QEvent::KeyPress, key, Qt::NoModifier));
    }
  });
  timer.start();
  while (busy()) QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 50);
  timer.stop();
  QObject::disconnect(onHover);
  QObject::disconnect(onPaint);
  return out;
}

void report(const char* what, const Probes& p) {
  std::cout << "  " << what << ": 16 ms timer late " << summarise(p.timerLate)
            << "\n    hover -> read-out " << summarise(p.hover) << "\n    pan key -> repainted "
            << summarise(p.pan) << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QStandardPaths::setTestModeEnabled(true);  // the window's QSettings go to a scratch location
  QCoreApplication::setOrganizationName("SonarGridBench");
  QCoreApplication::setApplicationName("bench_remap_latency");
  const QStringList args = app.arguments();
  auto option = [&](const QString& name, const QString& fallback) {
    const qsizetype i = args.indexOf(name);
    return i >= 0 && i + 1 < args.size() ? args[i + 1] : fallback;
  };
  if (args.size() < 2 || args[1].startsWith("--")) {
    std::cerr << "usage: bench_remap_latency LOG [--model M] [--rule R] [--param NAME] "
                 "[--steps N] [--pose odom|truth] [--cell METRES] [--controller] [--probe N] "
                 "[--reference REF] [--metrics]\n";
    return 2;
  }
  try {
    auto data = std::make_shared<const sg::Dataset>(sg::readSglog(args[1].toStdString()));
    sg::MapperSettings settings;
    settings.model = option("--model", "hpf").toStdString();
    settings.rule = option("--rule", "addition").toStdString();
    settings.parameters = sg::defaultParameters(settings.model, settings.rule);
    settings.pose =
        option("--pose", "odom") == "truth" ? sg::PoseSource::Truth : sg::PoseSource::Odometry;
    const std::string param =
        option("--param", QString::fromStdString(settings.parameters.specs().front().name))
            .toStdString();
    const sg::ParameterSpec* spec = nullptr;
    for (const auto& s : settings.parameters.specs())
      if (s.name == param) spec = &s;
    if (!spec) throw std::runtime_error("unknown --param " + param);
    const int steps = std::max(2, option("--steps", "40").toInt());
    const int probes = std::max(0, option("--probe", "0").toInt());
    const double cell = option("--cell", "0.05").toDouble();
    const bool bare = args.contains("--controller");
    const bool metrics = args.contains("--metrics");
    const QString referencePath = option("--reference", QString());
    if (bare && (metrics || !referencePath.isEmpty()))
      throw std::runtime_error("--metrics and --reference need the window (not --controller)");

    // The machine's speed now: one thread re-mapping the log with the default parameters, best of
    // three. A shared VM runs at very different speeds from one minute to the next; this line lets
    // two reports be compared.
    {
      sg::Mapper reference(data->ring, data->fittingGrid(settings.pose, cell), settings);
      double best = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        QElapsedTimer clock;
        clock.start();
        reference.reset();
        for (const sg::Scan& scan : data->scans) reference.integrate(scan);
        best = std::min(best, static_cast<double>(clock.nsecsElapsed()) * 1e-6);
      }
      std::cout << "  machine: one-thread re-map with default parameters " << best << " ms\n";
    }

    // Either the whole window or a bare controller + view.
    std::unique_ptr<sg::app::MainWindow> window;
    std::unique_ptr<sg::ui::GridView> bareView;
    std::unique_ptr<sg::ui::RemapController> bareRemap;
    sg::ui::GridView* view = nullptr;
    sg::ui::RemapController* remap = nullptr;
    QSlider* slider = nullptr;
    if (bare) {
      bareView = std::make_unique<sg::ui::GridView>();
      bareRemap = std::make_unique<sg::ui::RemapController>();
      view = bareView.get();
      remap = bareRemap.get();
      view->resize(1000, 700);
      QObject::connect(remap, &sg::ui::RemapController::mapped, view,
                       [view](std::shared_ptr<const sg::OccupancyMap> map, double, quint64, bool) {
                         view->setMap(std::move(map));
                       });
      view->show();
    } else {
      window = std::make_unique<sg::app::MainWindow>();
      window->resize(1280, 800);
      window->setCellSize(cell);
      window->setMapperSettings(settings);
      if (!referencePath.isEmpty() && !window->openReference(referencePath, true))
        throw std::runtime_error("cannot read the reference");
      window->show();
      view = window->gridView();
      remap = window->remapController();
      slider = window->parameterPanel()->sliderFor(QString::fromStdString(param));
      if (!slider) throw std::runtime_error("the panel has no slider for " + param);
    }

    // Repaints after the newest map arrived; the clock stops at the first one.
    bool shown = false;
    QElapsedTimer sinceMapped;
    double mappedToShown = 0.0;
    QObject::connect(remap, &sg::ui::RemapController::mapped, view,
                     [&](auto, double, quint64, bool) {
                       shown = false;
                       sinceMapped.start();
                     });
    QObject::connect(view, &sg::ui::GridView::repainted, [&] {
      if (!shown) mappedToShown = static_cast<double>(sinceMapped.nsecsElapsed()) * 1e-6;
      shown = true;
    });
    // The first repaint after a change that shows its settings, a preview (the window's
    // RemapController::setPreview, on a slow log) or the full map.
    quint64 stepGeneration = 0;
    bool stepHasMap = false;
    double firstShownMs = -1.0;
    int previews = 0;
    QElapsedTimer stepClock;
    auto mapArrived = [&](quint64 g) {
      if (g == stepGeneration) stepHasMap = true;
    };
    QObject::connect(remap, &sg::ui::RemapController::previewed, [&](auto, double, quint64 g) {
      if (g == stepGeneration) ++previews;
      mapArrived(g);
    });
    QObject::connect(remap, &sg::ui::RemapController::mapped,
                     [&](auto, double, quint64 g, bool) { mapArrived(g); });
    QObject::connect(view, &sg::ui::GridView::repainted, [&] {
      if (stepHasMap && firstShownMs < 0.0)
        firstShownMs = static_cast<double>(stepClock.nsecsElapsed()) * 1e-6;
    });
    // Connected before the log is opened: the first map may arrive while openLog() waits.
    quint64 lastDelivered = 0;
    QObject::connect(remap, &sg::ui::RemapController::mapped,
                     [&](auto, double, quint64 g, bool) { lastDelivered = g; });
    auto waitForNewest = [&](quint64 generation) {
      while (!(lastDelivered == generation && shown))
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
    };
    if (bare)
      remap->start(data, cell, settings, std::numeric_limits<double>::infinity());
    else if (!window->openLog(args[1], true))
      return 2;
    waitForNewest(remap->latestGeneration());  // warm-up: first map, view fitted
    sg::ui::MetricsPanel* panel = window ? window->findChild<sg::ui::MetricsPanel*>() : nullptr;
    // The panel shows the numbers of the newest full map: nothing scheduled or running, and the
    // result shown is that of its newest request (made when that map arrived).
    auto waitForMetrics = [&] {
      while (panel->busy() || panel->shownGeneration() != panel->generation())
        QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
    };
    if (metrics) {
      if (!panel) throw std::runtime_error("the window has no metrics panel");
      waitForMetrics();
    }

    // Slider positions (panel) or values (bare) across the range.
    auto change = [&](int i) {
      const double f = (i + 0.5) / steps;
      if (slider) {
        slider->setValue(static_cast<int>(
            std::lround(slider->minimum() + f * (slider->maximum() - slider->minimum()))));
      } else {
        const double v = spec->min + (spec->max - spec->min) * f;
        settings.parameters.set(param, spec->integer ? std::round(v) : v);
        remap->setSettings(settings);
      }
    };
    std::vector<double> ms, remapMs, handling, drawing, delivered, first, panelMs, computeMs;
    const auto timing =
        QObject::connect(remap, &sg::ui::RemapController::mapped,
                         [&](auto, double t, quint64, bool) { remapMs.push_back(t); });
    for (int i = 0; i < steps; ++i) {
      QElapsedTimer clock;
      clock.start();
      stepClock.start();
      stepHasMap = false;
      firstShownMs = -1.0;
      stepGeneration = remap->latestGeneration() + 1;
      const quint64 before = remap->latestGeneration();
      change(i);
      if (remap->latestGeneration() == before) continue;  // the same slider position
      handling.push_back(static_cast<double>(clock.nsecsElapsed()) * 1e-6);
      waitForNewest(remap->latestGeneration());
      ms.push_back(static_cast<double>(clock.nsecsElapsed()) * 1e-6);
      first.push_back(firstShownMs);
      drawing.push_back(mappedToShown);
      delivered.push_back(ms.back() - mappedToShown);
      if (metrics) {
        waitForMetrics();
        panelMs.push_back(static_cast<double>(clock.nsecsElapsed()) * 1e-6);
        if (panel->result()) computeMs.push_back(panel->result()->elapsedMs);
      }
    }
    QObject::disconnect(timing);
    const auto grid = view->map()->spec;
    std::cout << args[1].toStdString() << ": " << data->readingCount() << " readings, grid "
              << grid.width << " x " << grid.height << " cells of " << grid.cellSize << " m, "
              << settings.model << " x " << settings.rule << ", "
              << (bare ? "RemapController + GridView" : "MainWindow panel slider") << " " << param
              << " over " << ms.size() << " steps, "
              << (view->backend() == sg::ui::GridView::Backend::OpenGL ? "OpenGL" : "raster")
              << " view\n  change -> repainted " << summarise(ms)
              << "\n  change -> first repaint showing it (" << previews << " of " << ms.size()
              << " a preview) " << summarise(first) << "\n  worker re-map alone  "
              << summarise(remapMs) << "\n  change -> map delivered on the GUI thread "
              << summarise(delivered) << "\n  GUI thread: the change itself " << summarise(handling)
              << "\n  GUI thread: map delivered -> repainted " << summarise(drawing) << '\n';
    if (metrics)
      std::cout << "  metrics panel (" << (referencePath.isEmpty() ? "goodness" : "reference")
                << "): change -> panel refreshed " << summarise(panelMs)
                << "\n  metrics panel: its computation alone " << summarise(computeMs) << '\n';

    if (probes > 0) {
      QElapsedTimer idle;
      idle.start();
      report("idle (1 s)", probe(*view, [&] { return idle.elapsed() < 1000; }));
      int done = 0;
      quint64 waitingFor = 0;
      const auto next = [&] {
        change(done % steps);
        if (remap->latestGeneration() == waitingFor) change((done + steps / 2) % steps);
        waitingFor = remap->latestGeneration();
      };
      next();
      const auto chain = QObject::connect(remap, &sg::ui::RemapController::mapped,
                                          [&](auto, double, quint64 g, bool) {
                                            if (g != waitingFor) return;
                                            if (++done < probes) next();
                                          });
      report("while re-mapping", probe(*view, [&] { return done < probes; }));
      QObject::disconnect(chain);
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_remap_latency: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
