// SPDX-License-Identifier: BSD-3-Clause
#include "csmCasterCollection.h"

#include "csmCasterPreparation.h"
#include "csmProps.h"
#include "csmVTKMath.h"

#include "vtkActor.h"
#include "vtkCascadedShadowBlockMapper.h"
#include "vtkCascadedShadowMapPlanner.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace
{
/// Most receiver boxes a caster without self-shadow is tested against
/// (CullCastersWithoutReceivers); beyond, every caster is drawn.
constexpr size_t kMaxReceiverTests = 4096;
constexpr size_t kMaxReceiverBoxes = 64;
/// Most casters the cascade count is weighed with one by one (each is tested against every
/// cascade of every count planned).
constexpr size_t kMaxCasterLoads = 256;

/// Bounds of a prop that draws 3D geometry, or false (2D actors, invisible, no bounds).
bool propBounds(vtkProp* prop, double bounds[6])
{
  if (!prop || !prop->GetVisibility() || !prop->GetUseBounds())
  {
    return false;
  }
  const double* b = prop->GetBounds();
  if (!b || !(b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5]))
  {
    return false;
  }
  std::copy(b, b + 6, bounds);
  return true;
}

/// Does any caster draw lines wider or points bigger than one pixel (its map then depends on
/// the main view)?
template <typename Caster>
bool hasScreenSizedCasters(const std::vector<Caster>& casters)
{
  vtkNew<vtkPropCollection> actors;
  for (const Caster& caster : casters)
  {
    caster.Prop->GetActors(actors);
  }
  vtkCollectionSimpleIterator it;
  actors->InitTraversal(it);
  while (vtkProp* prop = actors->GetNextProp(it))
  {
    float sizes[2];
    csmScreenSizes(prop, sizes);
    if (sizes[0] > 1.0f || sizes[1] > 1.0f)
    {
      return true;
    }
  }
  return false;
}

/// Widens box (x0, x1, y0, y1, z0, z1) to hold other.
void uniteBoxes(std::array<double, 6>& box, const std::array<double, 6>& other)
{
  for (int k = 0; k < 3; ++k)
  {
    box[2 * k] = std::min(box[2 * k], other[2 * k]);
    box[2 * k + 1] = std::max(box[2 * k + 1], other[2 * k + 1]);
  }
}
} // namespace

csmCasterCollection::csmCasterCollection() = default;

csmCasterCollection::~csmCasterCollection()
{
  // Preparations under way stop at their next check (their futures wait for them below).
  for (auto& entry : this->Closures)
  {
    this->Retire(entry.second.Pending);
  }
  for (auto& entry : this->Blocks)
  {
    this->Retire(entry.second.Pending);
  }
  this->RetiredWork.clear();
}

template <typename T>
void csmCasterCollection::Retire(Preparation<T>& preparation)
{
  if (!preparation.Result.valid())
  {
    return;
  }
  preparation.Cancel->store(true);
  auto held = std::make_shared<std::future<std::shared_ptr<T>>>(std::move(preparation.Result));
  this->RetiredWork.emplace_back(
    [held]() { return held->wait_for(std::chrono::seconds(0)) == std::future_status::ready; });
  preparation = Preparation<T>();
}

void csmCasterCollection::DropStoppedWork()
{
  this->RetiredWork.erase(std::remove_if(this->RetiredWork.begin(), this->RetiredWork.end(),
                            [](const std::function<bool()>& stopped) { return stopped(); }),
    this->RetiredWork.end());
}

vtkPolyData* csmCasterCollection::SnapshotOf(vtkPolyData* data)
{
  // Copies of the arrays themselves: a shallow copy of the polydata would share the
  // application's vtkPoints and vtkCellArray objects, which it may resize, re-initialize or give
  // new arrays while a worker reads them.
  vtkSmartPointer<vtkPolyData>& snapshot = this->Snapshots[data];
  if (snapshot)
  {
    return snapshot;
  }
  snapshot = vtkSmartPointer<vtkPolyData>::New();
  if (vtkPoints* points = data->GetPoints(); points && points->GetData())
  {
    vtkNew<vtkPoints> owned;
    owned->SetData(csmOwnCopy(points->GetData()));
    snapshot->SetPoints(owned);
  }
  // (Both cell arrays set, even empty: a worker never makes one.)
  snapshot->SetPolys(csmOwnCopy(data->GetPolys()));
  snapshot->SetStrips(csmOwnCopy(data->GetStrips()));
  return snapshot;
}

template <typename T, typename Work>
void csmCasterCollection::StartPreparation(
  Preparation<T>& preparation, vtkPolyData* data, Work&& work)
{
  this->Retire(preparation);
  preparation.Cancel = std::make_shared<std::atomic<bool>>(false);
  preparation.Time = csmGeometryTime(data);
  vtkSmartPointer<vtkPolyData> copy = this->SnapshotOf(data);
  preparation.Result = std::async(std::launch::async,
    [copy, cancel = preparation.Cancel, work = std::forward<Work>(work)]()
    { return work(copy, cancel.get()); });
}

bool csmCasterCollection::MayPrepare(vtkPolyData* data, Pace& pace) const
{
  const vtkMTimeType time = csmGeometryTime(data);
  const long long wait = 1LL << std::min(pace.ShortLived, 10);
  if (pace.SeenTime != time)
  {
    // A new version: did the last one live long enough for its preparation to pay?
    if (pace.StartFrame >= 0)
    {
      pace.ShortLived = this->FrameNumber - pace.StartFrame <= 2 * wait ? pace.ShortLived + 1 : 0;
    }
    pace.SeenTime = time;
    pace.SeenFrame = this->FrameNumber;
    pace.StartFrame = -1;
    return false;
  }
  if (pace.StartFrame >= 0 || !this->ViewMoved || this->FrameNumber - pace.SeenFrame < wait)
  {
    return false;
  }
  pace.StartFrame = this->FrameNumber;
  return true;
}

double csmCasterCollection::CellsOf(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkMapper* mapper = actor ? actor->GetMapper() : nullptr;
  vtkDataObject* data =
    mapper && mapper->GetNumberOfInputPorts() > 0 && mapper->GetNumberOfInputConnections(0) > 0
    ? mapper->GetInputDataObject(0, 0)
    : nullptr;
  // A polydata's polygons and strips as the triangles they draw (a quad is two, a strip one a
  // point past its second), its lines and vertices as cells.
  if (vtkPolyData* poly = vtkPolyData::SafeDownCast(data))
  {
    return csmTriangleCount(poly) + static_cast<double>(poly->GetNumberOfLines()) +
      static_cast<double>(poly->GetNumberOfVerts());
  }
  return data ? static_cast<double>(data->GetNumberOfElements(vtkDataObject::CELL)) : 0.0;
}

void csmCasterCollection::ForgetTheGone(vtkWindow* window)
{
  // Forget the closed-surface answers for data that is gone, and the blocks of data or props
  // that are gone (releasing their buffers in this window's context, which is current).
  // A preparation for data that is gone is retired, not waited for.
  for (auto it = this->Closures.begin(); it != this->Closures.end();)
  {
    if (!it->second.Data)
    {
      this->Retire(it->second.Pending);
    }
    it = it->second.Data ? std::next(it) : this->Closures.erase(it);
  }
  for (auto it = this->Blocks.begin(); it != this->Blocks.end();)
  {
    const bool gone = !it->second.Window || !it->second.Data;
    if (gone && it->second.Window == window && it->second.Mapper)
    {
      it->second.Mapper->ReleaseGraphicsResources(window);
    }
    if (gone)
    {
      this->Retire(it->second.Pending);
    }
    it = gone ? this->Blocks.erase(it) : std::next(it);
  }
  this->DropStoppedWork();
  for (auto it = this->Proxies.begin(); it != this->Proxies.end();)
  {
    it = it->second.Window && it->second.Prop ? std::next(it) : this->Proxies.erase(it);
  }
}

csmCasterCollection::Counts csmCasterCollection::Collect(vtkRenderer* renderer,
  const Options& options, long long frame, bool viewMoved, csmFrameCasters& props)
{
  this->FrameNumber = frame;
  this->ViewMoved = viewMoved;
  this->Snapshots.clear(); // (the workers hold theirs)
  this->AdoptLastBlocks(renderer->GetRenderWindow());
  this->ForgetTheGone(renderer->GetRenderWindow());
  Counts counts;
  const int buildsBefore = this->BlockBuilds;
  // Casters: visible opaque props. Receivers: every visible prop; their boxes fit the cascades.
  vtkPropCollection* collection = renderer->GetViewProps();
  vtkCollectionSimpleIterator pit;
  collection->InitTraversal(pit);
  while (vtkProp* prop = collection->GetNextProp(pit))
  {
    std::array<double, 6> b;
    if (!propBounds(prop, b.data()))
    {
      continue;
    }
    props.Receivers.push_back(b);
    if (!prop->HasOpaqueGeometry())
    {
      props.TranslucentReceivers = true;
      continue;
    }
    const int closure = this->ClosureOf(prop, options.CullClosedCasters);
    counts.ClosedCasters += closure != 0 ? 1 : 0;
    const size_t first = props.Casters.size();
    if (options.CompactCasters &&
      this->AddCompactCaster(
        prop, closure, static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow()), props))
    {
      ++counts.CompactCasters;
    }
    else
    {
      csmFrameCasters::Caster caster;
      caster.Prop = prop;
      caster.Bounds = b;
      caster.Closure = closure;
      caster.Cells = csmCasterCollection::CellsOf(prop);
      props.Casters.push_back(caster);
    }
    const bool itself = this->ShadowsItself(prop, options.CullCastersWithoutReceivers);
    for (size_t i = first; i < props.Casters.size(); ++i)
    {
      csmFrameCasters::Caster& caster = props.Casters[i];
      caster.ShadowsItself = itself;
      caster.Receiver = static_cast<int>(props.Receivers.size()) - 1;
      float sizes[2];
      csmScreenSizes(caster.Prop, sizes);
      const bool screenSized = sizes[0] > 1.0f || sizes[1] > 1.0f;
      if (caster.Compact < 0)
      {
        props.CasterLoads.push_back(
          { caster.Bounds, caster.Cells, caster.Receiver, itself, screenSized });
        continue;
      }
      const csmFrameCasters::Compact& compact = props.Compacts[static_cast<size_t>(caster.Compact)];
      for (const csmFrameCasters::Compact::Group& group : compact.Groups)
      {
        props.CasterLoads.push_back(
          { group.Bounds, group.Cells, caster.Receiver, itself, screenSized });
      }
    }
  }
  props.ScreenSized = hasScreenSizedCasters(props.Casters);
  counts.PreparedBlocks = this->BlockBuilds - buildsBefore;
  return counts;
}

namespace
{

/// The polydata of a prop that may be drawn from compact blocks: a plain actor and mapper,
/// polygons or strips drawn as a surface, nothing else (see CompactCasters).
vtkPolyData* compactableData(vtkProp* prop)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  // Subclasses (followers, LOD actors, impostor and splat mappers) draw what their class knows.
  if (!data || !property || std::strcmp(actor->GetClassName(), "vtkOpenGLActor") != 0 ||
    std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") != 0 ||
    property->GetRepresentation() != VTK_SURFACE || mapper->GetNumberOfClippingPlanes() > 0 ||
    data->GetNumberOfVerts() > 0 || data->GetNumberOfLines() > 0 ||
    data->GetNumberOfPolys() + data->GetNumberOfStrips() == 0)
  {
    return nullptr;
  }
  return data;
}

}

void csmCasterCollection::AdoptLastBlocks(vtkWindow* window)
{
  // Which props' last blocks serve their new data (addresses only: the last data may be gone,
  // and its address taken by another prop's new data, which at worst spares nothing here).
  struct Adoption
  {
    vtkPolyData* Last;
    vtkPolyData* Data;
    csmCellsKey Cells;
  };
  std::vector<Adoption> adoptions;
  for (const auto& [key, proxy] : this->Proxies)
  {
    vtkPolyData* data = key.first == window && proxy.Prop ? compactableData(proxy.Prop) : nullptr;
    const auto from = this->Blocks.find({ window, proxy.Data });
    const auto to = this->Blocks.find({ window, data });
    if (!data || data == proxy.Data || from == this->Blocks.end() || from->second.BlockOf.empty() ||
      !from->second.Mapper || (to != this->Blocks.end() && to->second.Data == data))
    {
      continue;
    }
    // (Gone: nobody draws it; alive: its address is its own.)
    const bool drawsLast = from->second.Data &&
      std::any_of(this->Proxies.begin(), this->Proxies.end(),
        [&](const auto& other)
        {
          return other.first.first == window && other.second.Prop &&
            other.second.Prop != proxy.Prop && compactableData(other.second.Prop) == proxy.Data;
        });
    const csmCellsKey cells = csmCellsOf(data);
    if (!drawsLast && cells.SameCells(from->second.Source))
    {
      adoptions.push_back({ proxy.Data, data, cells });
    }
  }
  // Taken out first, then put where their new data is, so that one's new key may be another's
  // last.
  std::vector<CasterBlocks> taken;
  for (const Adoption& a : adoptions)
  {
    const auto from = this->Blocks.find({ window, a.Last });
    taken.emplace_back(from != this->Blocks.end() ? std::move(from->second) : CasterBlocks());
    if (from != this->Blocks.end())
    {
      this->Blocks.erase(from);
    }
  }
  for (size_t k = 0; k < adoptions.size(); ++k)
  {
    CasterBlocks& blocks = taken[k];
    CasterBlocks& to = this->Blocks[{ window, adoptions[k].Data }];
    if (!blocks.Mapper || to.Data == adoptions[k].Data)
    {
      this->Retire(blocks.Pending);
      if (blocks.Mapper)
      {
        blocks.Mapper->ReleaseGraphicsResources(window); // (two props took the same data)
      }
      continue;
    }
    if (to.Mapper && to.Window == window)
    {
      to.Mapper->ReleaseGraphicsResources(window); // a gone data's, at the same address
    }
    this->Retire(to.Pending);
    blocks.Data = adoptions[k].Data;
    blocks.Time = 0;                    // (not current: its boxes follow the points)
    blocks.Source = adoptions[k].Cells; // (this data's arrays now)
    blocks.SourceFrame = this->FrameNumber;
    to = std::move(blocks);
    const auto closure = this->Closures.find(adoptions[k].Last);
    Closure& next = this->Closures[adoptions[k].Data];
    if (closure != this->Closures.end() && next.Data != adoptions[k].Data)
    {
      next.Topology = std::move(closure->second.Topology);
    }
  }
}

const csmCasterCollection::Closure& csmCasterCollection::ClassifiedShape(vtkPolyData* data)
{
  Closure& closure = this->Closures[data];
  if (closure.Data == data && closure.Time == csmGeometryTime(data))
  {
    return closure;
  }
  closure.Data = data;
  // Until it is classified, a shape counts as open (drawn with both sides, its full bias) and
  // as one that may shadow itself: correct, only without the savings of a closed one.
  closure.Orientation = 0;
  closure.Planar = false;
  closure.ShadowsItself = true;
  const double triangles = csmTriangleCount(data);
  if (triangles > vtkCascadedShadows::MostClassifiedTriangles)
  {
    closure.Time = csmGeometryTime(data); // not classified: what it costs outweighs what it saves
    return closure;
  }
  csm::SurfaceClosure c;
  if (triangles <= vtkCascadedShadows::SynchronousPreparationTriangles)
  {
    c = csmClassifyPolyData(data, nullptr, &closure.Topology);
  }
  else
  {
    // A big mesh is classified by a worker thread; frames go on meanwhile (from the second
    // frame that draws it on, as its blocks).
    if (!closure.Pending.Result.valid() || closure.Pending.Time != csmGeometryTime(data))
    {
      if (closure.Pending.Result.valid())
      {
        this->Retire(closure.Pending); // its data changed
      }
      if (this->MayPrepare(data, closure.Paced))
      {
        this->StartPreparation(closure.Pending, data,
          [](vtkPolyData* copy, const std::atomic<bool>* stop)
          {
            auto prepared = std::make_shared<csmPreparedClosure>();
            prepared->Closure = csmClassifyPolyData(copy, stop);
            return prepared;
          });
      }
      return closure;
    }
    if (closure.Pending.Result.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    {
      return closure;
    }
    c = closure.Pending.Result.get()->Closure;
    closure.Pending = Preparation<csmPreparedClosure>();
  }
  closure.Time = csmGeometryTime(data);
  closure.Orientation = c.closed && c.volume != 0.0 ? (c.volume > 0.0 ? 1 : -1) : 0;
  closure.Planar = c.planar;
  closure.ShadowsItself = c.canShadowItself();
  return closure;
}

bool csmCasterCollection::ShadowsItself(vtkProp* prop, bool cullWithoutReceivers)
{
  // Only surfaces drawn as they are, by the plain mapper (impostor and splat mappers draw
  // spheres and discs around the points, which stand out of a plane): lines and points may be
  // drawn as tubes and spheres, and the user's clipping planes open a solid (its inside then
  // shows).
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  if (!cullWithoutReceivers || !data || !property ||
    std::strcmp(mapper->GetClassName(), "vtkOpenGLPolyDataMapper") != 0 ||
    property->GetRepresentation() != VTK_SURFACE || data->GetNumberOfVerts() > 0 ||
    data->GetNumberOfLines() > 0)
  {
    return true;
  }
  const Closure& closure = this->ClassifiedShape(data);
  return mapper->GetNumberOfClippingPlanes() > 0 ? !closure.Planar : closure.ShadowsItself;
}

int csmCasterCollection::ClosureOf(vtkProp* prop, bool cullClosed)
{
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  vtkPolyDataMapper* mapper = actor ? vtkPolyDataMapper::SafeDownCast(actor->GetMapper()) : nullptr;
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  vtkProperty* property = actor ? actor->GetProperty() : nullptr;
  // (A prop with translucent geometry is not drawn into the maps as a closed surface: its far
  // faces show through its near ones, lit inside.)
  if (!cullClosed || !data || !property || !prop->HasOpaqueGeometry() ||
    prop->HasTranslucentPolygonalGeometry() || property->GetRepresentation() != VTK_SURFACE ||
    property->GetBackfaceCulling() || property->GetFrontfaceCulling() ||
    mapper->GetNumberOfClippingPlanes() > 0 || data->GetNumberOfVerts() > 0 ||
    data->GetNumberOfLines() > 0)
  {
    return 0;
  }
  const Closure& closure = this->ClassifiedShape(data);
  const double determinant = actor->GetMatrix()->Determinant();
  if (closure.Orientation == 0 || !std::isfinite(determinant) || determinant == 0.0)
  {
    return 0;
  }
  return determinant > 0.0 ? closure.Orientation : -closure.Orientation;
}

bool csmCasterCollection::FollowPoints(
  CasterBlocks& blocks, vtkPolyData* data, vtkMTimeType dataTime) const
{
  // Only the points moved (the same cells of as many points: a deforming mesh, a time step
  // that edits its positions): the blocks keep their triangles, their boxes follow the points.
  vtkPolyData* input = blocks.Mapper ? blocks.Mapper->GetInput() : nullptr;
  std::vector<std::array<double, 6>> bounds;
  const bool sameCells =
    blocks.SourceFrame == this->FrameNumber || csmCellsOf(data) == blocks.Source;
  if (!input || blocks.BlockOf.empty() || !sameCells ||
    !csmBlockBounds(data, blocks.BlockOf, blocks.Cells.size(), bounds))
  {
    return false;
  }
  blocks.Bounds = std::move(bounds);
  blocks.Time = dataTime;
  if (input->GetPoints() != data->GetPoints())
  {
    input->SetPoints(data->GetPoints());
  }
  return true;
}

bool csmCasterCollection::PreparedBlocks(vtkPolyData* data, vtkOpenGLRenderWindow* window)
{
  // The data's blocks in this window, prepared again when the data changed: a small mesh at
  // once, a big one by a worker thread while the frames draw the prop as it is (correct, only
  // without culling inside it) until the blocks are ready.
  CasterBlocks& blocks = this->Blocks[{ window, data }];
  const vtkMTimeType dataTime = csmGeometryTime(data);
  // (Prepared for this very data, into blocks or into nothing usable.)
  const bool current = blocks.Data == data && blocks.Window == window && blocks.Time == dataTime;
  if (!current && blocks.Data == data && blocks.Window == window &&
    this->FollowPoints(blocks, data, dataTime))
  {
    return blocks.Mapper->HasTriangles();
  }
  if (!current)
  {
    std::shared_ptr<csmPreparedBlocks> prepared;
    const size_t triangles = static_cast<size_t>(csmTriangleCount(data));
    const size_t perBlock = std::max<size_t>(vtkCascadedShadows::MinimumBlockTriangles,
      (triangles + vtkCascadedShadows::MaximumBlocks - 1) / vtkCascadedShadows::MaximumBlocks);
    if (blocks.Data != data || blocks.Window != window)
    {
      this->Retire(blocks.Pending);
      blocks.Window = window;
      blocks.Data = data;
      blocks.Paced = Pace();
    }
    if (triangles <= vtkCascadedShadows::SynchronousPreparationTriangles)
    {
      // A small mesh at once, from its own data (this thread's).
      this->Retire(blocks.Pending);
      prepared = csmPrepareBlocks(data, perBlock, nullptr);
    }
    else
    {
      // A big mesh is prepared once a later frame's view moved (the maps that follow a moving
      // view are drawn again and again; a still view keeps its maps): a single image (a
      // screenshot, a batch frame, even rendered twice) never waits for, nor holds the memory
      // of, its preparation.
      if (blocks.Pending.Result.valid() && blocks.Pending.Time != dataTime)
      {
        this->Retire(blocks.Pending); // its data changed
      }
      if (!blocks.Pending.Result.valid())
      {
        if (this->MayPrepare(data, blocks.Paced))
        {
          this->StartPreparation(blocks.Pending, data,
            [perBlock](vtkPolyData* copy, const std::atomic<bool>* stop)
            { return csmPrepareBlocks(copy, perBlock, stop); });
        }
        return false; // (picked up in a later frame, whenever it is ready)
      }
      if (blocks.Pending.Result.wait_for(std::chrono::seconds(0)) == std::future_status::timeout)
      {
        return false;
      }
      prepared = blocks.Pending.Result.get();
      blocks.Pending = Preparation<csmPreparedBlocks>();
    }
    if (blocks.Mapper)
    {
      blocks.Mapper->ReleaseGraphicsResources(window);
    }
    blocks.Mapper = nullptr;
    blocks.Bounds.clear();
    blocks.Cells.clear();
    blocks.BlockOf.clear();
    blocks.Time = dataTime;
    blocks.Build = ++this->BlockBuilds;
    if (prepared->Blocks.empty() || prepared->Points != data->GetNumberOfPoints())
    {
      return false; // nothing usable (no area, a bad index or position): drawn as it is
    }
    // The prop's own points (the vertex buffer its mapper uploads serves both, through the
    // window's buffer cache), the blocks' triangles.
    auto input = vtkSmartPointer<vtkPolyData>::New();
    input->SetPoints(data->GetPoints());
    blocks.Mapper = vtkSmartPointer<vtkCascadedShadowBlockMapper>::New();
    blocks.Mapper->SetInputData(input);
    blocks.Mapper->ScalarVisibilityOff();
    for (const auto& block : prepared->Blocks)
    {
      blocks.Cells.push_back(static_cast<double>(block.second));
    }
    blocks.Bounds = std::move(prepared->Bounds);
    if (triangles <= vtkCascadedShadows::SynchronousPreparationTriangles)
    {
      blocks.BlockOf = std::move(prepared->BlockOf); // (from this very data, read just now)
      blocks.Source = csmCellsOf(data);
    }
    blocks.Mapper->SetBlocks(std::move(prepared->Corners), std::move(prepared->Blocks));
  }
  return blocks.Mapper && blocks.Mapper->HasTriangles();
}

bool csmCasterCollection::AddCompactCaster(
  vtkProp* prop, int closure, vtkOpenGLRenderWindow* window, csmFrameCasters& props)
{
  vtkPolyData* data = compactableData(prop);
  if (!data || !window)
  {
    return false;
  }
  if (!this->PreparedBlocks(data, window))
  {
    return false;
  }
  const CasterBlocks& blocks = this->Blocks[{ window, data }];
  // The prop's actor for its blocks: its property, a copy of its matrix.
  vtkActor* actor = vtkActor::SafeDownCast(prop);
  CasterProxy& proxy = this->Proxies[{ window, prop }];
  if (proxy.Prop != prop || proxy.Window != window || proxy.Data != data ||
    proxy.Build != blocks.Build)
  {
    proxy.Prop = prop;
    proxy.Window = window;
    proxy.Data = data;
    proxy.Build = blocks.Build;
    proxy.Matrix = vtkSmartPointer<vtkMatrix4x4>::New();
    proxy.Actor = vtkSmartPointer<vtkActor>::New();
    proxy.Actor->SetMapper(blocks.Mapper);
    proxy.Actor->SetUserMatrix(proxy.Matrix);
  }
  vtkMatrix4x4* matrix = actor->GetMatrix();
  if (!std::equal(matrix->GetData(), matrix->GetData() + 16, proxy.Matrix->GetData()))
  {
    proxy.Matrix->DeepCopy(matrix);
  }
  proxy.Actor->SetProperty(actor->GetProperty());
  csmFrameCasters::Compact compact;
  compact.Mapper = blocks.Mapper;
  compact.Cells = blocks.Cells;
  for (const std::array<double, 6>& local : blocks.Bounds)
  {
    // The block's box in world space: the box of its corners' images.
    std::array<double, 6> world = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
      -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[4] = { local[corner & 1], local[2 + ((corner >> 1) & 1)],
        local[4 + ((corner >> 2) & 1)], 1.0 };
      double q[4];
      matrix->MultiplyPoint(p, q);
      for (int k = 0; k < 3; ++k)
      {
        const double v = q[k] / q[3];
        world[2 * k] = std::min(world[2 * k], v);
        world[2 * k + 1] = std::max(world[2 * k + 1], v);
      }
    }
    if (!std::all_of(world.begin(), world.end(), [](double v) { return std::isfinite(v); }))
    {
      return false; // a matrix that sends a corner to infinity: the prop is drawn as it is
    }
    compact.Bounds.push_back(world);
  }
  const std::size_t perGroup = vtkCascadedShadows::BlocksPerGroup;
  for (std::size_t first = 0; first < compact.Bounds.size(); first += perGroup)
  {
    csmFrameCasters::Compact::Group group;
    group.First = first;
    group.Count = std::min(perGroup, compact.Bounds.size() - first);
    group.Bounds = compact.Bounds[first];
    for (std::size_t b = first; b < first + group.Count; ++b)
    {
      uniteBoxes(group.Bounds, compact.Bounds[b]);
      group.Cells += compact.Cells[b];
    }
    compact.Groups.push_back(group);
  }
  std::array<double, 6> whole = compact.Bounds.front();
  for (const auto& group : compact.Groups)
  {
    uniteBoxes(whole, group.Bounds);
  }
  csmFrameCasters::Caster caster;
  caster.Prop = proxy.Actor;
  caster.Bounds = whole;
  caster.Closure = closure;
  caster.Compact = static_cast<int>(props.Compacts.size());
  props.Compacts.push_back(std::move(compact));
  props.Casters.push_back(caster);
  return true;
}

bool csmFrameCasters::CasterHasReceivers(const Caster& caster, const double* travel) const
{
  // Directional lights only.
  if (caster.ShadowsItself || caster.Receiver < 0 || !travel ||
    this->Receivers.size() > kMaxReceiverTests)
  {
    return true;
  }
  // A shadow shorter than a millionth of the caster is no shadow (the lookup's bias hides it);
  // not of the scene, which a prop far off makes longer than the caster's distance to the
  // ground under it.
  const double* s = caster.Bounds.data();
  const double minimum = 1e-6 *
    std::sqrt((s[1] - s[0]) * (s[1] - s[0]) + (s[3] - s[2]) * (s[3] - s[2]) +
      (s[5] - s[4]) * (s[5] - s[4]));
  for (size_t r = 0; r < this->Receivers.size(); ++r)
  {
    if (static_cast<int>(r) != caster.Receiver &&
      csmCasterBoxReachesBox(travel, caster.Bounds.data(), this->Receivers[r].data(), minimum))
    {
      return true;
    }
  }
  return false;
}

void csmFrameCasters::GatherAcrossProcesses(vtkMultiProcessController* controller)
{
  // All processes plan from the global bounds and the same receiver boxes, and re-render when
  // any of them saw a change.
  double* sceneBounds = this->SceneBounds;
  double lo[3] = { sceneBounds[0], sceneBounds[2], sceneBounds[4] };
  double hi[3] = { sceneBounds[1], sceneBounds[3], sceneBounds[5] };
  double globalLo[3], globalHi[3];
  controller->AllReduce(lo, globalLo, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(hi, globalHi, 3, vtkCommunicator::MAX_OP);
  for (int i = 0; i < 3; ++i)
  {
    sceneBounds[2 * i] = globalLo[i];
    sceneBounds[2 * i + 1] = globalHi[i];
  }
  int changed = this->Changed ? 1 : 0, anyChanged = 0;
  controller->AllReduce(&changed, &anyChanged, 1, vtkCommunicator::MAX_OP);
  this->Changed = anyChanged != 0;
  // The caster loads of every process (padded with loads of no cells).
  {
    // Box, cells, shadows itself, screen-sized (their receiver indices are each process's
    // own: dropped).
    constexpr size_t n = 9;
    std::vector<csmFrameCasters::CasterLoad>& loads = this->CasterLoads;
    int mineCount = static_cast<int>(loads.size()), mostLoads = 0;
    controller->AllReduce(&mineCount, &mostLoads, 1, vtkCommunicator::MAX_OP);
    std::vector<double> mineLoads(n * static_cast<size_t>(mostLoads), 0.0), allLoads;
    for (int i = 0; i < mineCount; ++i)
    {
      double* out = mineLoads.data() + n * i;
      std::copy(loads[i].Bounds.begin(), loads[i].Bounds.end(), out);
      out[6] = loads[i].Cells;
      out[7] = loads[i].ShadowsItself ? 1.0 : 0.0;
      out[8] = loads[i].ScreenSized ? 1.0 : 0.0;
    }
    allLoads.resize(mineLoads.size() * controller->GetNumberOfProcesses());
    controller->AllGather(
      mineLoads.data(), allLoads.data(), static_cast<vtkIdType>(mineLoads.size()));
    loads.clear();
    for (size_t i = 0; i + n <= allLoads.size(); i += n)
    {
      if (allLoads[i + 6] > 0.0) // (padding has no cells)
      {
        csmFrameCasters::CasterLoad load;
        std::copy(allLoads.begin() + i, allLoads.begin() + i + 6, load.Bounds.begin());
        load.Cells = allLoads[i + 6];
        load.ShadowsItself = allLoads[i + 7] != 0.0;
        load.ScreenSized = allLoads[i + 8] != 0.0;
        loads.push_back(load);
      }
    }
  }
  // The receiver boxes of every process (padded with empty boxes).
  std::vector<std::array<double, 6>>& receivers = this->Receivers;
  int count = static_cast<int>(receivers.size()), most = 0;
  controller->AllReduce(&count, &most, 1, vtkCommunicator::MAX_OP);
  std::vector<double> mine(6 * static_cast<size_t>(most), 0.0), all;
  for (int i = 0; i < most; ++i)
  {
    for (int k = 0; k < 6; ++k)
    {
      mine[6 * i + k] = i < count ? receivers[i][k] : (k % 2 == 0 ? 1.0 : -1.0);
    }
  }
  all.resize(mine.size() * controller->GetNumberOfProcesses());
  controller->AllGather(mine.data(), all.data(), static_cast<vtkIdType>(mine.size()));
  receivers.clear();
  for (size_t i = 0; i + 5 < all.size(); i += 6)
  {
    if (all[i] <= all[i + 1])
    {
      receivers.push_back({ all[i], all[i + 1], all[i + 2], all[i + 3], all[i + 4], all[i + 5] });
    }
  }
}

void csmCasterCollection::ReleaseGraphicsResources(vtkWindow* w)
{
  for (auto it = this->Blocks.begin(); it != this->Blocks.end();)
  {
    if (w && it->second.Window != w)
    {
      ++it;
      continue;
    }
    vtkWindow* context = w ? w : it->second.Window.GetPointer();
    if (it->second.Mapper && context)
    {
      it->second.Mapper->ReleaseGraphicsResources(context);
    }
    this->Retire(it->second.Pending);
    it = this->Blocks.erase(it);
  }
  for (auto it = this->Proxies.begin(); it != this->Proxies.end();)
  {
    it = !w || it->second.Window == w ? this->Proxies.erase(it) : std::next(it);
  }
}

void csmFrameCasters::FeedPlanner(vtkCascadedShadowMapPlanner* planner) const
{
  // The receivers' boxes fit the cascades (up to kMaxReceiverBoxes; beyond, the box around all
  // of them).
  planner->ClearReceiverBounds();
  if (this->Receivers.size() <= kMaxReceiverBoxes)
  {
    for (const auto& b : this->Receivers)
    {
      planner->AddReceiverBounds(b.data());
    }
  }
  // What each cascade's pass would draw weighs the cascade count (up to kMaxCasterLoads
  // casters; beyond, one load of all their cells in the scene's box, which every cascade draws).
  // Screen-sized casters (tubes, spheres, wide lines) cost their fragments, not their cells,
  // and have no fixed extent: with any of them the count is the fewest that meets the target
  // and there is no scene-fitted map (Tried.md, "Screen-sized casters").
  planner->ClearCasterLoads();
  const bool screenSizedCasters = std::any_of(this->CasterLoads.begin(), this->CasterLoads.end(),
    [](const csmFrameCasters::CasterLoad& l) { return l.ScreenSized; });
  if (!screenSizedCasters && this->CasterLoads.size() <= kMaxCasterLoads)
  {
    for (const auto& load : this->CasterLoads)
    {
      planner->AddCasterLoad(load.Bounds.data(), load.Cells,
        this->Receivers.size() <= kMaxReceiverBoxes ? load.Receiver : -1, load.ShadowsItself,
        load.ScreenSized);
    }
  }
  else if (!screenSizedCasters)
  {
    double cells = 0.0;
    for (const auto& load : this->CasterLoads)
    {
      cells += load.Cells;
    }
    planner->AddCasterLoad(this->SceneBounds, cells);
  }
}
