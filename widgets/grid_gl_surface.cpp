// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_gl_surface.h"

#include <QPainter>
#include <algorithm>

#include "grid_view.h"

namespace sg::ui {
namespace {

// GLSL 1.10 / ES 1.00: runs on every context Qt may hand us (compatibility, core via Qt's
// rewriting is not needed since the default surface format is 2.x compatibility).
const char* const kVertexShader = R"(
attribute vec2 corner;
void main() { gl_Position = vec4(corner, 0.0, 1.0); }
)";

// The cell under each fragment's centre, exactly as renderGridCells() computes it:
// cell = floor(offset + pixel * scale), pixel measured from the top-left corner.
const char* const kFragmentShader = R"(
#ifdef GL_ES
precision highp float;
#endif
uniform sampler2D levels;
uniform sampler2D palette;
uniform vec2 cellOffset;
uniform vec2 cellScale;
uniform vec2 gridSize;
uniform float framebufferHeight;
uniform vec4 background;
void main() {
  vec2 pixel = vec2(gl_FragCoord.x, framebufferHeight - gl_FragCoord.y);
  vec2 cell = floor(cellOffset + pixel * cellScale);
  if (cell.x < 0.0 || cell.y < 0.0 || cell.x >= gridSize.x || cell.y >= gridSize.y) {
    gl_FragColor = background;
    return;
  }
  float level = floor(texture2D(levels, (cell + 0.5) / gridSize).r * 255.0 + 0.5);
  gl_FragColor = texture2D(palette, vec2((min(level, 16.0) + 0.5) / 32.0, 0.5));
}
)";

}  // namespace

GridGlSurface::GridGlSurface(GridView* view) : QOpenGLWidget(view), view_(view) {}

GridGlSurface::~GridGlSurface() {
  if (!context()) return;
  makeCurrent();
  releaseTextures();
  quad_.destroy();
  doneCurrent();
}

void GridGlSurface::releaseTextures() {
  if (levelTexture_) glDeleteTextures(1, &levelTexture_);
  if (paletteTexture_) glDeleteTextures(1, &paletteTexture_);
  levelTexture_ = paletteTexture_ = 0;
  textureWidth_ = textureHeight_ = 0;
}

void GridGlSurface::initializeGL() {
  initializeOpenGLFunctions();
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize_);
  ready_ = program_.addShaderFromSourceCode(QOpenGLShader::Vertex, kVertexShader) &&
           program_.addShaderFromSourceCode(QOpenGLShader::Fragment, kFragmentShader) &&
           program_.link();
  if (!ready_) {
    qWarning("GridView: the palette shader did not build (%s); drawing on the CPU instead",
             qPrintable(program_.log()));
    return;
  }
  static const GLfloat corners[] = {-1.f, -1.f, 1.f, -1.f, -1.f, 1.f, 1.f, 1.f};
  quad_.create();
  quad_.bind();
  quad_.allocate(corners, sizeof(corners));
  quad_.release();
  glGenTextures(1, &levelTexture_);
  glGenTextures(1, &paletteTexture_);
  for (GLuint t : {levelTexture_, paletteTexture_}) {
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  textureWidth_ = textureHeight_ = 0;
  levelsDirty_ = paletteDirty_ = true;
}

void GridGlSurface::uploadPalette() {
  // 32 entries (a power of two): the 16 levels, then the unknown colour (index 16, a never-observed
  // cell) repeated.
  constexpr int kEntries = 32;
  std::uint8_t rgba[kEntries * 4];
  for (int k = 0; k < kEntries; ++k) {
    const Rgb& c = k < kLevels ? view_->palette_[static_cast<std::size_t>(k)] : kUnknownColour;
    rgba[4 * k] = c.r;
    rgba[4 * k + 1] = c.g;
    rgba[4 * k + 2] = c.b;
    rgba[4 * k + 3] = 255;
  }
  glBindTexture(GL_TEXTURE_2D, paletteTexture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, kEntries, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  paletteDirty_ = false;
}

void GridGlSurface::uploadLevels() {
  const OccupancyMap* map = view_->scene_.map.get();
  levelsDirty_ = false;
  uploadFirst_ = uploadCount_ = 0;
  if (!map) return;
  const GridSpec& g = map->spec;
  // The colour index of each cell: its level, or 16 (unknown) where no reading wrote it.
  std::vector<std::uint8_t> shown = map->level;
  if (map->observed.size() == shown.size())
    for (std::size_t i = 0; i < shown.size(); ++i)
      if (map->observed[i] == 0) shown[i] = static_cast<std::uint8_t>(kLevels);
  glBindTexture(GL_TEXTURE_2D, levelTexture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (g.width != textureWidth_ || g.height != textureHeight_ || uploaded_.size() != shown.size()) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, g.width, g.height, 0, GL_LUMINANCE,
                 GL_UNSIGNED_BYTE, shown.data());
    textureWidth_ = g.width;
    textureHeight_ = g.height;
    uploaded_ = shown;
    uploadFirst_ = 0;
    uploadCount_ = g.height;
    return;
  }
  // Only the band of rows that changed: a scrub step or a local edit touches a few rows.
  const auto w = static_cast<std::size_t>(g.width);
  int first = -1, last = -1;
  for (int row = 0; row < g.height; ++row) {
    const auto begin = static_cast<std::size_t>(row) * w;
    if (!std::equal(shown.begin() + static_cast<std::ptrdiff_t>(begin),
                    shown.begin() + static_cast<std::ptrdiff_t>(begin + w),
                    uploaded_.begin() + static_cast<std::ptrdiff_t>(begin))) {
      if (first < 0) first = row;
      last = row;
    }
  }
  if (first < 0) return;
  const auto offset = static_cast<std::size_t>(first) * w;
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, first, g.width, last - first + 1, GL_LUMINANCE,
                  GL_UNSIGNED_BYTE, shown.data() + offset);
  std::copy(shown.begin() + static_cast<std::ptrdiff_t>(offset),
            shown.begin() + static_cast<std::ptrdiff_t>((static_cast<std::size_t>(last) + 1) * w),
            uploaded_.begin() + static_cast<std::ptrdiff_t>(offset));
  uploadFirst_ = first;
  uploadCount_ = last - first + 1;
}

void GridGlSurface::paintGL() {
  const QSize size = view_->size();
  const OccupancyMap* map = view_->scene_.map.get();
  const bool fits = map && map->spec.width > 0 && map->spec.height > 0 &&
                    map->level.size() == map->spec.cellCount() &&
                    map->spec.width <= maxTextureSize_ && map->spec.height <= maxTextureSize_;
  if (!ready_ || !fits) {
    // No shader, or a grid larger than a texture may be: the CPU picture, same pixels.
    QPainter painter(this);
    painter.drawImage(0, 0, renderGridCells(map, view_->palette_, view_->view_, size));
    paintOverlays(painter, view_->scene_, view_->palette_, view_->overlays_, view_->view_, size);
    if (view_->tool_) view_->tool_->paint(painter, view_->view_, size);
    painter.end();
    view_->surfacePainted();
    return;
  }
  // Our GL calls go between begin/endNativePainting so that QPainter's engine, which caches GL
  // state (enabled attribute arrays, bound program), restores its own before the overlays.
  QPainter painter(this);
  painter.beginNativePainting();
  if (paletteDirty_) uploadPalette();
  if (levelsDirty_) uploadLevels();

  const qreal dpr = devicePixelRatioF();
  const int fbWidth = static_cast<int>(size.width() * dpr + 0.5);
  const int fbHeight = static_cast<int>(size.height() * dpr + 0.5);
  glViewport(0, 0, fbWidth, fbHeight);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);

  // cellX = (x - ox) / c with x = cx + (px / dpr - W / 2) / s; likewise y, which grows upwards.
  const ViewTransform& t = view_->view_;
  const GridSpec& g = map->spec;
  const double k = 1.0 / (t.pixelsPerMetre * g.cellSize * dpr);
  const double offsetX = (t.centre.x() - g.origin.x()) / g.cellSize -
                         size.width() / (2.0 * t.pixelsPerMetre * g.cellSize);
  const double offsetY = (t.centre.y() - g.origin.y()) / g.cellSize +
                         size.height() / (2.0 * t.pixelsPerMetre * g.cellSize);
  const QColor bg = backgroundColour();

  program_.bind();
  program_.setUniformValue("levels", 0);
  program_.setUniformValue("palette", 1);
  program_.setUniformValue("cellOffset",
                           QVector2D(static_cast<float>(offsetX), static_cast<float>(offsetY)));
  program_.setUniformValue("cellScale", QVector2D(static_cast<float>(k), static_cast<float>(-k)));
  program_.setUniformValue("gridSize",
                           QVector2D(static_cast<float>(g.width), static_cast<float>(g.height)));
  program_.setUniformValue("framebufferHeight", static_cast<GLfloat>(fbHeight));
  program_.setUniformValue("background", bg);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, paletteTexture_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, levelTexture_);
  quad_.bind();
  const int corner = program_.attributeLocation("corner");
  program_.enableAttributeArray(corner);
  program_.setAttributeBuffer(corner, GL_FLOAT, 0, 2);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  program_.disableAttributeArray(corner);
  quad_.release();
  program_.release();
  painter.endNativePainting();

  const QSize pixels(fbWidth, fbHeight);
  if (overlaysDirty_ || overlays_.size() != pixels) {
    overlays_ = QImage(pixels, QImage::Format_ARGB32_Premultiplied);
    overlays_.setDevicePixelRatio(dpr);
    overlays_.fill(Qt::transparent);
    QPainter overlayPainter(&overlays_);
    paintOverlays(overlayPainter, view_->scene_, view_->palette_, view_->overlays_, view_->view_,
                  size);
    overlaysDirty_ = false;
  }
  painter.drawImage(0, 0, overlays_);
  if (view_->tool_) {
    // Drawn by the raster engine too, like the overlays; small, so drawn again on every paint.
    QImage tool(pixels, QImage::Format_ARGB32_Premultiplied);
    tool.setDevicePixelRatio(dpr);
    tool.fill(Qt::transparent);
    QPainter toolPainter(&tool);
    view_->tool_->paint(toolPainter, view_->view_, size);
    toolPainter.end();
    painter.drawImage(0, 0, tool);
  }
  painter.end();
  view_->surfacePainted();
}

}  // namespace sg::ui
