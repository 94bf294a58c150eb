// The transport-model interface: each model's row (name, BSDF family), views, light maps and passes, the
// plan deciding photon passes from them, and a frame shading with the model's
// integrator (its indirect view is the analytic ambient term without photons).
#include "core/bsdf.h"
#include "io/shapes.h"
#include "plan/render_plan.h"
#include "plan/transport_model.h"
#include "support/render_fixtures.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

// A diffuse floor under a point light, with a mirror sphere and a glass sphere.
Scene floorAndSpheres(ShadingModel model) {
  Scene scene;
  scene.render.model = model;
  Material floor = makeMaterial("floor", Color(0.3f, 0.2f, 0.1f), Color(0.5f));
  floor.pR = 0.5f;
  Material mirror = makeMaterial("mirror", Color(0.0f), Color(0.0f));
  mirror.kr = 1.0f;
  mirror.specular = Color(1.0f);
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  glass.ior = 1.5f;
  scene.materials = {floor, mirror, glass};
  scene.meshes.push_back(makeQuad(Vec3(-5, 0, 5), Vec3(10, 0, 0), Vec3(0, 0, -10), 0));
  scene.spheres = {{Vec3(-1, 1, 0), 1.0f, 1}, {Vec3(1.5f, 1, 0), 1.0f, 2}};
  scene.lights = {point(Vec3(0, 4, 0), Color(1.0f), 10.0f)};
  scene.render.ambient = Color(0.5f);
  scene.photons.indirectPhotons = scene.photons.globalPhotons = scene.photons.causticPhotons = 1000;
  scene.camera = axisCamera(Vec3(0, 3, 8), Vec3(0, 0, 0));
  scene.camera.width = 8;
  scene.camera.height = 6;
  scene.camera.spp = 1;
  return scene;
}

TEST(TransportModel, ClassicLacksOnlyTheDirectAndCausticViews) {
  for (size_t i = 0; i < kViewNames.size(); ++i) {
    const Aov aov = static_cast<Aov>(i);
    EXPECT_EQ(classicTransport().hasView(aov), aov != Aov::Direct && aov != Aov::Caustic) << viewName(aov);
    EXPECT_TRUE(physicalTransport().hasView(aov)) << viewName(aov);
  }
}

TEST(TransportModel, ThePlanRunsOnlyTheModelsOwnLightMaps) {
  // The physical model's volume map is its own too, but on only with a medium (test_plan_media).
  struct Case {
    ShadingModel model;
    std::vector<MapKind> on, off, own;
  };
  const MapKind global = MapKind::Global, caustic = MapKind::Caustic;
  for (const Case& c : {Case{ShadingModel::Classic, {MapKind::Indirect}, {global, caustic, MapKind::Volume}, {MapKind::Indirect}},
                        Case{ShadingModel::Physical, {global, caustic}, {MapKind::Indirect}, {global, caustic, MapKind::Volume}}}) {
    const Scene scene = floorAndSpheres(c.model);
    const TransportModel& model = transportOf(scene);
    const RenderPlan plan = makePlan(scene, Aov::Beauty);
    EXPECT_EQ(plan.model, &model);
    EXPECT_EQ(model.lightMaps(), c.own);
    for (MapKind k : c.on) EXPECT_TRUE(plan[photonPass(k)].on) << model.name() << " " << mapName(k);
    for (MapKind k : c.off) {
      EXPECT_FALSE(plan[photonPass(k)].on) << model.name() << " " << mapName(k);
      EXPECT_NE(plan[photonPass(k)].reason.find(std::string("the ") + model.name() + " model has no"),
                std::string::npos)
          << plan[photonPass(k)].reason;
    }
    // A view that does not read a map leaves it off: depth reads none.
    const RenderPlan depth = makePlan(scene, Aov::Depth);
    for (MapKind k : c.on) EXPECT_FALSE(depth[photonPass(k)].on) << mapName(k);
  }
}

TEST(TransportModel, ProgressivePassesEmitTheGatePhotonsOnceAndNoOtherModelsMap) {
  PerMap<bool> all;
  for (MapKind k : kAllMaps) all[k] = true;
  const PerMap<bool> classic = classicTransport().emittedMaps(all, 0);
  EXPECT_TRUE(classic[MapKind::Shadow] && classic[MapKind::Indirect]);
  EXPECT_FALSE(classic[MapKind::Global] || classic[MapKind::Caustic]);
  const PerMap<bool> first = physicalTransport().emittedMaps(all, 0), later = physicalTransport().emittedMaps(all, 1);
  EXPECT_TRUE(first[MapKind::Shadow] && first[MapKind::Global] && first[MapKind::Caustic]);
  EXPECT_FALSE(first[MapKind::Indirect]);
  EXPECT_FALSE(later[MapKind::Shadow]);
  EXPECT_TRUE(later[MapKind::Global] && later[MapKind::Caustic]);
  EXPECT_TRUE(first[MapKind::Volume] && later[MapKind::Volume]);  // fresh each pass, like the surface maps
  EXPECT_FALSE(classic[MapKind::Volume]);

  Scene scene = floorAndSpheres(ShadingModel::Physical);
  scene.photons.passes = 4;
  EXPECT_EQ(physicalTransport().passes(scene, Aov::Beauty), 4);
  EXPECT_EQ(physicalTransport().passes(scene, Aov::Depth), 1);
  // Classic passes take new camera samples over pass 0's maps.
  EXPECT_EQ(classicTransport().passes(scene, Aov::Beauty), 4);
  EXPECT_EQ(classicTransport().passes(scene, Aov::Depth), 1);
  EXPECT_TRUE(physicalTransport().freshPhotonsEachPass());
  EXPECT_FALSE(classicTransport().freshPhotonsEachPass());
}

TEST(TransportModel, TheFrameShadesWithTheModelsIntegrator) {
  for (ShadingModel m : {ShadingModel::Classic, ShadingModel::Physical}) {
    const Scene scene = floorAndSpheres(m);
    const FrameChoices choices = choicesOf(makePlan(scene, Aov::Beauty), scene);
    EXPECT_EQ(choices.integrator, &transportOf(scene).integrator());
    // Classic glass tints shadow rays; physical glass blocks them (caustics carry that light).
    EXPECT_EQ(choices.integrator->glass, m == ShadingModel::Classic ? GlassShadows::Tint : GlassShadows::Block);
  }
}

TEST(TransportModel, TheSceneChoosesItsModelsRowAndFamily) {
  for (ShadingModel m : {ShadingModel::Classic, ShadingModel::Physical}) {
    const Scene scene = floorAndSpheres(m);
    const TransportModel& model = transportOf(scene);
    EXPECT_EQ(model.id(), m);
    EXPECT_EQ(&model.info(), &modelOf(scene.render));
    EXPECT_STREQ(model.integrator().name, model.name());
    // The family decides the BSDF: the classic model's materials shade as the report's Phong.
    const BsdfType type = makeBsdf(scene.materials[0], model.info().bsdf, scene.photons.sampling).type;
    EXPECT_EQ(type == BsdfType::ClassicPhong, m == ShadingModel::Classic);
  }
  EXPECT_EQ(modelOf(RenderSettings{}).id, kDefaultShadingModel);
}

TEST(TransportModel, ClassicIndirectViewWithoutPhotonsIsTheAmbientTerm) {
  const Scene scene = floorAndSpheres(ShadingModel::Classic);
  Rig rig(scene);
  rig.ctx.choices = choicesOf(makePlan(scene, Aov::Indirect), scene);
  const Image image = rig.render(Aov::Indirect);
  // Every pixel on the floor: material ambient x render.ambient; on the black spheres 0.
  int floorPixels = 0;
  for (const Color& c : image.pixels) {
    if (c.r > 0.0f) {
      expectColorNear(c, Color(0.15f, 0.1f, 0.05f), 1e-6f);
      ++floorPixels;
    }
  }
  EXPECT_GT(floorPixels, 0);
}

}  // namespace
}  // namespace penumbra
