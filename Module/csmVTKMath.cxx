// SPDX-License-Identifier: BSD-3-Clause
#include "csmVTKMath.h"

#include "csmCulling.h"
#include "csmGeometry.h"
#include "csmReuse.h"

#include "vtkCamera.h"
#include "vtkMath.h"

#include <cmath>

glm::dmat4 csmFromRowMajor(const double m[16])
{
  glm::dmat4 matrix;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      matrix[column][row] = m[4 * row + column];
    }
  }
  return matrix;
}

void csmToRowMajor(const glm::dmat4& m, double out[16])
{
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      out[4 * row + column] = m[column][row]; // glm is column-major
    }
  }
}

bool csmToCamera(vtkCamera* camera, double aspect, csm::Camera& cam)
{
  if (!camera)
  {
    return false;
  }
  double v[3];
  camera->GetPosition(v);
  cam.wsPosition = { v[0], v[1], v[2] };
  camera->GetDirectionOfProjection(v);
  cam.wsDirection = { v[0], v[1], v[2] };
  camera->GetViewUp(v);
  cam.wsViewUp = { v[0], v[1], v[2] };
  camera->GetClippingRange(v);
  cam.vsNear = v[0];
  cam.vsFar = v[1];
  cam.aspect = aspect;
  cam.parallel = camera->GetParallelProjection() != 0;
  cam.parallelScale = camera->GetParallelScale();
  cam.fovyDeg = camera->GetViewAngle();
  if (camera->GetUseHorizontalViewAngle() && aspect > 0.0)
  {
    const double halfX = vtkMath::RadiansFromDegrees(0.5 * camera->GetViewAngle());
    cam.fovyDeg = vtkMath::DegreesFromRadians(2.0 * std::atan(std::tan(halfX) / aspect));
  }
  // A window centre shifted off the axis (a magnified screenshot's tiles): the frustum about the
  // axis that holds the shifted one, its pixels as large as the shifted one's
  // (csmWindowCentreScale for the image height).
  const double* centre = camera->GetWindowCenter();
  const double sx = 1.0 + std::abs(centre[0]), sy = csmWindowCentreScale(camera);
  if (std::isfinite(sx) && std::isfinite(sy) && (sx > 1.0 || sy > 1.0))
  {
    cam.aspect = aspect * sx / sy;
    cam.parallelScale *= sy;
    const double halfY = vtkMath::RadiansFromDegrees(0.5 * cam.fovyDeg);
    cam.fovyDeg = vtkMath::DegreesFromRadians(2.0 * std::atan(sy * std::tan(halfY)));
  }
  return true;
}

bool csmCameraOnAxis(vtkCamera* camera)
{
  return camera && camera->GetWindowCenter()[0] == 0.0 && camera->GetWindowCenter()[1] == 0.0 &&
    !camera->GetUseOffAxisProjection() && !camera->GetUseExplicitProjectionTransformMatrix();
}

double csmWindowCentreScale(vtkCamera* camera)
{
  const double y = camera ? std::abs(camera->GetWindowCenter()[1]) : 0.0;
  return std::isfinite(y) ? 1.0 + y : 1.0;
}

bool csmIsSmallCameraStep(vtkCamera* before, vtkCamera* now, double aspect, double depth)
{
  csm::Camera a, b;
  return before && now && csmToCamera(before, aspect, a) && csmToCamera(now, aspect, b) &&
    csm::smallCameraStep(a, b, depth);
}

bool csmCascadeReachesBox(const double worldToClip[16], const double bounds[6], bool depthClamp)
{
  if (!worldToClip || !bounds)
  {
    return false;
  }
  return !csm::boxOutsideClipVolume(
    csmFromRowMajor(worldToClip), csm::Bounds::fromMinMaxPairs(bounds), depthClamp);
}

bool csmViewSeesOnlyOutsideOf(vtkCamera* camera, double aspect, const double bounds[6])
{
  csm::Camera cam;
  return bounds && csmToCamera(camera, aspect, cam) &&
    csm::eyeSeesOnlyOutsideOf(cam, csm::Bounds::fromMinMaxPairs(bounds));
}

bool csmCasterBoxReachesBox(const double lightDirection[3], const double casterBounds[6],
  const double receiverBounds[6], double minimumDistance)
{
  if (!lightDirection || !casterBounds || !receiverBounds)
  {
    return true;
  }
  return csm::sweptBoxReachesBox(csm::Bounds::fromMinMaxPairs(casterBounds),
    glm::dvec3(lightDirection[0], lightDirection[1], lightDirection[2]),
    csm::Bounds::fromMinMaxPairs(receiverBounds), minimumDistance);
}
