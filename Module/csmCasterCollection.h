// SPDX-License-Identifier: BSD-3-Clause
// The casters and receivers of a frame (vtkCascadedShadowMapBakerPass's internal part): which
// visible props cast, their world boxes, their closed-surface classification and compact blocks
// (kept across frames while their data does not change, big meshes prepared by worker threads),
// and which of them can shadow anything under a light.
#ifndef csmCasterCollection_h
#define csmCasterCollection_h

#include "csmCasterPreparation.h"      // for csmCellsKey
#include "vtkCascadedShadowMapTypes.h" // for the compact casters' limits
#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkWeakPointer.h"

#include <array>
#include <atomic>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <utility>
#include <vector>

class vtkActor;
class vtkCascadedShadowBlockMapper;
class vtkCascadedShadowMapPlanner;
class vtkMatrix4x4;
class vtkMultiProcessController;
class vtkOpenGLRenderWindow;
class vtkPolyData;
class vtkProp;
class vtkRenderer;
class vtkWindow;

/// What a frame draws: the visible props' boxes and the opaque ones among them.
struct csmFrameCasters
{
  double SceneBounds[6] = { 1, -1, 1, -1, 1, -1 };
  bool Changed = true; ///< a prop, light, option or the window size changed: render every map
  /// Else, the world boxes (before and after) of the casters whose shadow changed: a kept map
  /// draws again only the texels they cover.
  std::vector<std::array<double, 6>> Dirty;
  /// Some caster's geometry or place changed (Changed, or Dirty not empty).
  bool GeometryChanged = true;
  struct Caster
  {
    vtkProp* Prop = nullptr;      ///< a visible opaque prop, or an actor of a prop's blocks
    std::array<double, 6> Bounds; ///< world box
    /// 0 draw both sides; +1 / -1 closed, its counter-clockwise faces (after the actor's
    /// matrix) turned outward / inward.
    int Closure = 0;
    /// Drawn from compact blocks (CompactCasters): its entry in Compacts (-1: as it is).
    int Compact = -1;
    /// The prop may shadow itself (false: planar, or closed and convex).
    bool ShadowsItself = true;
    /// Its prop's box in Receivers (-1: none).
    int Receiver = -1;
    double Cells = 0.0; ///< what its data draws (CellsOf): triangles, lines, vertices
  };
  std::vector<Caster> Casters;
  /// A prop drawn from compact blocks: the mapper that draws the chosen ones, each block's
  /// world box and triangles, and the groups of consecutive blocks
  /// (vtkCascadedShadows::BlocksPerGroup) the visible-depth pass and the cascade count weigh.
  struct Compact
  {
    vtkCascadedShadowBlockMapper* Mapper = nullptr;
    std::vector<std::array<double, 6>> Bounds;
    std::vector<double> Cells;
    struct Group
    {
      std::size_t First = 0, Count = 0; ///< its blocks
      std::array<double, 6> Bounds;
      double Cells = 0.0;
    };
    std::vector<Group> Groups;
  };
  std::vector<Compact> Compacts;
  std::vector<std::array<double, 6>> Receivers;
  /// Some receiver has no opaque geometry: the view's depth pass, which draws the casters,
  /// does not show where it is.
  bool TranslucentReceivers = false;
  /// What the cascade count and the scene-fitted map are judged by
  /// (vtkCascadedShadowMapPlanner::AddCasterLoad), per caster; all processes' when
  /// distributed (then without receiver boxes).
  struct CasterLoad
  {
    std::array<double, 6> Bounds;
    double Cells = 0.0; ///< what its data draws (CellsOf): triangles, lines, vertices
    int Receiver = -1;  ///< its prop's box in Receivers (-1: none)
    bool ShadowsItself = true;
    bool ScreenSized = false; ///< drawn wider than its data (tubes, spheres, wide lines)
  };
  std::vector<CasterLoad> CasterLoads;
  /// Some caster draws lines wider or points bigger than one pixel (its map then depends on the
  /// main view).
  bool ScreenSized = false;

  /// Does the caster shadow anything under a directional light that travels along
  /// lightTravel (CullCastersWithoutReceivers)? Always true for a caster that may shadow
  /// itself, for spot lights (lightTravel null) and with too many receivers to test.
  bool CasterHasReceivers(const Caster& caster, const double* lightTravel) const;
  /// The receivers' boxes and the casters' loads, for the planner (the cascades' fit and
  /// count).
  void FeedPlanner(vtkCascadedShadowMapPlanner* planner) const;
  /// Every process's scene bounds, change, caster loads and receiver boxes (distributed data).
  void GatherAcrossProcesses(vtkMultiProcessController* controller);
};

/// The visible props of a renderer as casters and receivers, and the caches that make that
/// cheap across frames.
class csmCasterCollection
{
public:
  struct Options
  {
    bool CullClosedCasters = true;
    bool CompactCasters = true;
    bool CullCastersWithoutReceivers = true;
  };
  /// What the last Collect() found: casters drawn from behind, from compact blocks, and the
  /// meshes prepared in blocks anew.
  struct Counts
  {
    int ClosedCasters = 0;
    int CompactCasters = 0;
    int PreparedBlocks = 0; ///< meshes whose blocks were built (not only moved) in this frame
  };

  csmCasterCollection();
  ~csmCasterCollection(); // stops the worker threads' preparations
  csmCasterCollection(const csmCasterCollection&) = delete;
  csmCasterCollection& operator=(const csmCasterCollection&) = delete;

  /// The renderer's visible props into casters, receivers and caster loads (props.SceneBounds
  /// and props.Changed are the caller's). frame numbers the Render() calls; viewMoved: this
  /// frame's camera moved (big meshes are prepared only then).
  Counts Collect(vtkRenderer* renderer, const Options& options, long long frame, bool viewMoved,
    csmFrameCasters& props);

  /// +1 / -1: the prop's data is closed, its counter-clockwise faces turned outward / inward in
  /// world space; 0: draw both sides (open, translucent, or cullClosed is off).
  int ClosureOf(vtkProp* prop, bool cullClosed);

  /// The blocks and proxies drawn in this window (all of them for no window).
  void ReleaseGraphicsResources(vtkWindow* window);

  /// What an actor's input data draws: a polydata's triangles (of its polygons and strips) and
  /// its line and vertex cells, other data's cells (0 for other props or without data).
  static double CellsOf(vtkProp* prop);

private:
  struct Closure;
  const Closure& ClassifiedShape(vtkPolyData* data);
  bool ShadowsItself(vtkProp* prop, bool cullWithoutReceivers);
  /// For a prop drawn from compact blocks, appends its blocks to the casters with their world
  /// boxes and returns true; false: the prop is drawn as it is.
  bool AddCompactCaster(
    vtkProp* prop, int closure, vtkOpenGLRenderWindow* window, csmFrameCasters& props);
  /// The data's blocks in this window, prepared (or their preparation started); false while
  /// there are none to draw.
  bool PreparedBlocks(vtkPolyData* data, vtkOpenGLRenderWindow* window);
  void ForgetTheGone(vtkWindow* window);
  /// A prop whose mapper took other data (a reader's next time step, a new polydata set as its
  /// input) of the same cells as the data it drew last keeps that data's blocks in this window
  /// (their boxes follow the new points) and hands that data's classification topology on, where
  /// no other prop in the window still draws the last data.
  void AdoptLastBlocks(vtkWindow* window);

  /// A worker thread's preparation of a big mesh: its result to come, the flag that stops it
  /// early, and the data time it was started for.
  template <typename T>
  struct Preparation
  {
    std::future<std::shared_ptr<T>> Result;
    std::shared_ptr<std::atomic<bool>> Cancel;
    vtkMTimeType Time = 0;
  };
  /// Starts `work` on a worker thread, on a copy of the data's points and cells the worker owns
  /// (the application may edit its data in place between renders); a preparation under way is
  /// retired first.
  template <typename T, typename Work>
  void StartPreparation(Preparation<T>& preparation, vtkPolyData* data, Work&& work);
  /// Cancels a preparation and keeps its worker until it stops, without waiting for it.
  template <typename T>
  void Retire(Preparation<T>& preparation);
  /// Drops the retired preparations whose workers stopped.
  void DropStoppedWork();
  /// When a big mesh is prepared: the data time a frame last saw and since when, the frame its
  /// last preparation started (-1: none since), and how many versions in a row changed soon
  /// after their preparation started (its result then serves a frame or two, or none).
  struct Pace
  {
    vtkMTimeType SeenTime = 0;
    long long SeenFrame = 0;
    long long StartFrame = -1;
    int ShortLived = 0;
  };
  /// May a big mesh's preparation start this frame? Once its data stayed the same since an
  /// earlier frame and the view moved; after each version of the data that changed within twice
  /// that wait of its preparation's start, the wait doubles (a mesh that changes every frame or
  /// two is drawn as it is, never prepared), and a version that outlived it starts the count
  /// again.
  bool MayPrepare(vtkPolyData* data, Pace& pace) const;
  /// The copy of a big mesh's points and cells for this frame's workers (one per data and
  /// frame).
  vtkPolyData* SnapshotOf(vtkPolyData* data);

  long long FrameNumber = 0;
  bool ViewMoved = false;
  std::map<vtkPolyData*, vtkSmartPointer<vtkPolyData>> Snapshots;
  std::vector<std::function<bool()>> RetiredWork; ///< each: true once its worker stopped
  /// csm::classifySurface's answer per polydata, kept while the data does not change.
  struct Closure
  {
    vtkWeakPointer<vtkPolyData> Data;
    vtkMTimeType Time = 0;
    int Orientation = 0; ///< +1 outward, -1 inward, 0 open
    bool Planar = false;
    bool ShadowsItself = true; ///< csm::SurfaceClosure::canShadowItself
    /// A mesh classified in its frame: its weld and whether its edges balance, so that its
    /// next points (a deforming mesh) do not sort its edges again (4 bytes a point).
    csm::SurfaceTopology Topology;
    Preparation<csmPreparedClosure> Pending; ///< a big mesh's, under way
    Pace Paced;
  };
  std::map<vtkPolyData*, Closure> Closures;
  /// Compact blocks of a polydata in one window (the mapper holds that context's buffers),
  /// and the preparation under way (a worker thread's, for a big mesh).
  struct CasterBlocks
  {
    vtkWeakPointer<vtkWindow> Window;
    vtkWeakPointer<vtkPolyData> Data;
    vtkMTimeType Time = 0; ///< of the data the blocks were prepared from
    int Build = 0;         ///< which build: the proxy of a prop follows it
    vtkSmartPointer<vtkCascadedShadowBlockMapper> Mapper;
    std::vector<std::array<double, 6>> Bounds; ///< per block, in the data's coordinates
    std::vector<double> Cells;                 ///< per block: its triangles
    /// A mesh prepared at once: each triangle's block, and the cells they were prepared from
    /// (the same cells with moved points keep the blocks, their boxes computed again).
    std::vector<std::uint16_t> BlockOf;
    csmCellsKey Source;
    long long SourceFrame = -1; ///< the frame Source was read from the data in (adopted blocks)
    Preparation<csmPreparedBlocks> Pending;
    Pace Paced;
  };
  std::map<std::pair<vtkWindow*, vtkPolyData*>, CasterBlocks> Blocks;
  /// Blocks prepared from the data's cells kept for its moved points, their boxes computed
  /// again (false: the cells changed, or the blocks were not prepared at once).
  bool FollowPoints(CasterBlocks& blocks, vtkPolyData* data, vtkMTimeType dataTime) const;
  /// The actor that draws a prop's blocks in one window (its property, a copy of its matrix).
  struct CasterProxy
  {
    vtkWeakPointer<vtkWindow> Window;
    vtkWeakPointer<vtkProp> Prop;
    vtkPolyData* Data = nullptr;
    int Build = 0;
    vtkSmartPointer<vtkActor> Actor;
    vtkSmartPointer<vtkMatrix4x4> Matrix;
  };
  std::map<std::pair<vtkWindow*, vtkProp*>, CasterProxy> Proxies;
  int BlockBuilds = 0;
};

#endif
