// Slider-change -> repainted-view latency (issue 5, item 10): drives RemapController + GridView as
// the parameter panel will, changing one parameter per step, and reports the median and p95 of the
// time from the request to the first repaint showing its map. Not run by ctest.
//
//   bench_remap_latency LOG [--model M] [--rule R] [--param NAME] [--steps N] [--pose odom|truth]
//
// It sweeps NAME (default: the model's first parameter) across its declared range in N steps
// (default 40), waiting for each map before the next request. Run it under xvfb-run for the OpenGL
// surface, or with QT_QPA_PLATFORM=offscreen for the raster one.

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <algorithm>
#include <iostream>

#include "grid_view.h"
#include "remap_controller.h"
#include "sonargrid/io/sglog.h"

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  const QStringList args = app.arguments();
  auto option = [&](const QString& name, const QString& fallback) {
    const qsizetype i = args.indexOf(name);
    return i >= 0 && i + 1 < args.size() ? args[i + 1] : fallback;
  };
  if (args.size() < 2 || args[1].startsWith("--")) {
    std::cerr << "usage: bench_remap_latency LOG [--model M] [--rule R] [--param NAME] "
                 "[--steps N] [--pose odom|truth]\n";
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

    sg::ui::GridView view;
    view.resize(1000, 700);
    view.show();
    sg::ui::RemapController remap;
    bool shown = false;
    QObject::connect(&remap, &sg::ui::RemapController::mapped, &view,
                     [&](std::shared_ptr<const sg::OccupancyMap> map, double, quint64, bool) {
                       view.setMap(std::move(map));
                       shown = false;
                     });
    QObject::connect(&view, &sg::ui::GridView::repainted, [&] { shown = true; });

    auto requestAndWait = [&](const sg::MapperSettings& s) {
      QElapsedTimer clock;
      clock.start();
      const quint64 before = remap.latestGeneration();
      bool delivered = false;
      const auto c =
          QObject::connect(&remap, &sg::ui::RemapController::mapped,
                           [&](auto, double, quint64 g, bool) { delivered = g == before + 1; });
      remap.setSettings(s);
      while (!(delivered && shown)) QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
      QObject::disconnect(c);
      return static_cast<double>(clock.nsecsElapsed()) * 1e-6;
    };
    remap.start(data, 0.05, settings, std::numeric_limits<double>::infinity());
    requestAndWait(settings);  // warm-up: first map, view fitted

    std::vector<double> ms;
    for (int i = 0; i < steps; ++i) {
      const double v = spec->min + (spec->max - spec->min) * (i + 0.5) / steps;
      settings.parameters.set(param, spec->integer ? std::round(v) : v);
      ms.push_back(requestAndWait(settings));
    }
    std::sort(ms.begin(), ms.end());
    auto quantile = [&](double q) {
      return ms[static_cast<std::size_t>(std::ceil(q * static_cast<double>(ms.size())) - 1)];
    };
    std::cout << args[1].toStdString() << ": " << data->readingCount() << " readings, "
              << settings.model << " x " << settings.rule << ", sweeping " << param << " over "
              << steps << " steps, "
              << (view.backend() == sg::ui::GridView::Backend::OpenGL ? "OpenGL" : "raster")
              << " view: request -> repainted median " << quantile(0.5) << " ms, p95 "
              << quantile(0.95) << " ms, max " << ms.back() << " ms\n";
  } catch (const std::exception& e) {
    std::cerr << "bench_remap_latency: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
