# Two renderers (viewports) sharing one pass chain, one with LightSpacePages... (pages is per baker; so
# use two chains sharing the one vtkCascadedShadowMapPass? -> here: same chain object on both renderers),
# then remove a renderer between frames.
import sys; sys.path.insert(0, "/tmp/breaker")
from common import *
exec(open("/tmp/breaker2/pages.py").read().split("A = field()")[0].split("NFR =")[0])
S = scene(size=(640,240)); ren1, win = S['ren'], S['win']
ren1.SetViewport(0,0,0.5,1)
p = install(S); chain = S['chain']
ren2 = vtk.vtkRenderer(); ren2.SetViewport(0.5,0,1,1); ren2.AddActor(S['ground']); ren2.AddActor(S['box'])
L = vtk.vtkLight(); L.SetLightTypeToSceneLight(); L.SetPositional(False); L.SetPosition(3,10,2); L.SetFocalPoint(0,0,0); ren2.AddLight(L)
ren2.GetActiveCamera().SetPosition(0,2.5,9); ren2.GetActiveCamera().SetFocalPoint(0,0,0); ren2.ResetCameraClippingRange()
ren2.SetPass(chain)   # the same chain on both
win.AddRenderer(ren2)
def shot(label):
    P = grab(win); r1 = ren1.GetPass(); r2 = ren2.GetPass(); ren1.SetPass(None); ren2.SetPass(None); N = grab(win); ren1.SetPass(r1); ren2.SetPass(r2)
    d = (P.sum(axis=2) < 0.85*N.sum(axis=2)-6); W = d.shape[1]//2
    print("%-50s shadowed left=%d right=%d brighter=%d glerr=%s" % (label, d[:, :W].sum(), d[:, W:].sum(), int((P.sum(axis=2) > 1.15*N.sum(axis=2)+6).sum()), gl_errors(win)), flush=True)
    return P
b = p.GetShadowMapBakerPass()
shot("shared chain, pages default")
for i in range(3): ren2.GetActiveCamera().Azimuth(20); ren2.ResetCameraClippingRange(); shot("orbit right %d" % i)
b.SetLightSpacePages(False); shot("pages off (shared)")
b.SetLightSpacePages(True); shot("pages on again")
# one paged, one not: give ren2 its own chain with pages off
p2 = CSMPass.UseShadowsOn(ren2); p2.GetShadowMapBakerPass().SetLightSpacePages(False)
for i in range(3): ren1.GetActiveCamera().Azimuth(15); ren1.ResetCameraClippingRange(); shot("own chains, ren2 unpaged, orbit left %d" % i)
win.RemoveRenderer(ren2); P = grab(win); print("removed ren2 -> rendered ok, mean %.1f glerr=%s" % (P.mean(), gl_errors(win)), flush=True)
ren1.GetActiveCamera().Azimuth(10); P = grab(win); print("after removal next frame ok mean %.1f" % P.mean(), flush=True)
win.AddRenderer(ren2); shot("ren2 re-added")
ren2.SetPass(chain); shot("ren2 back on shared chain")
win.RemoveRenderer(ren1); P = grab(win); print("removed ren1 (the installing renderer) ok mean %.1f" % P.mean(), flush=True)
del ren1; S['ren'] = None; import gc; gc.collect(); P = grab(win); print("ren1 deleted, frame ok mean %.1f glerr=%s" % (P.mean(), gl_errors(win)), flush=True)
win.RemoveRenderer(ren2); P = grab(win); print("no renderers frame ok", flush=True)
win.AddRenderer(ren2); P = grab(win); print("ren2 re-added alone mean %.1f" % P.mean(), flush=True)
win.Finalize(); print("finalized", flush=True)
