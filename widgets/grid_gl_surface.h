// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The OpenGL surface of GridView: the level layer lives in an 8-bit texture, a 16 x 1 palette
// texture recolours it in the fragment shader, and only the rows whose levels changed are sent
// again (glTexSubImage2D), as RViz does for occupancy grids. Overlays are drawn by the raster
// paint engine into a transparent image (kept until they change) and composited over the cells:
// the GL paint engine antialiases differently (not at all without multisampling), and the picture
// must be the raster path's.

#include <QImage>
#include <QOpenGLBuffer>
#include <QOpenGLFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLWidget>
#include <cstdint>
#include <vector>

namespace sg::ui {

class GridView;

class GridGlSurface : public QOpenGLWidget, protected QOpenGLFunctions {
 public:
  explicit GridGlSurface(GridView* view);
  ~GridGlSurface() override;

  void levelsChanged() { levelsDirty_ = true; }
  void paletteChanged() { paletteDirty_ = overlaysDirty_ = true; }
  void overlaysChanged() { overlaysDirty_ = true; }
  // Rows sent by the last upload (for tests and the benchmark): [first, first + count).
  int lastUploadFirstRow() const { return uploadFirst_; }
  int lastUploadRowCount() const { return uploadCount_; }

 protected:
  void initializeGL() override;
  void paintGL() override;

 private:
  void uploadLevels();
  void uploadPalette();
  void releaseTextures();

  GridView* view_;
  QOpenGLShaderProgram program_;
  QOpenGLBuffer quad_{QOpenGLBuffer::VertexBuffer};
  bool ready_ = false;  // shaders linked and textures created
  GLuint levelTexture_ = 0;
  GLuint paletteTexture_ = 0;
  int textureWidth_ = 0;
  int textureHeight_ = 0;
  GLint maxTextureSize_ = 0;
  std::vector<std::uint8_t> uploaded_;  // the levels the texture holds
  bool levelsDirty_ = true;
  bool paletteDirty_ = true;
  bool overlaysDirty_ = true;
  QImage overlays_;
  int uploadFirst_ = 0;
  int uploadCount_ = 0;
};

}  // namespace sg::ui
