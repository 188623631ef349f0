// The celadon museum page: loads museum.glb (celadon museum, docs/museum.md),
// turns its levels of detail into THREE.LOD objects, keeps the nearest lights,
// and walks it on a desktop (walk.js), a phone (touch.js) or in a WebXR
// headset (xr.js); a bar shows the bytes of museum.glb while it loads.
// window.museum reports what was loaded and what a frame costs (the tests and
// the HUD read it).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { VRButton } from 'three/addons/webxr/VRButton.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import { makeLods } from './lod.js';
import { LightPool } from './light_pool.js';
import { Obstacles } from './obstacles.js';
import { Walker } from './walk.js';
import { XrLocomotion } from './xr.js';
import { TouchControls } from './touch.js';
import { LabelPanel } from './label_panel.js';

const status = {
  ready: false, error: null, title: '', vessels: 0,
  triangles: 0, drawCalls: 0, trianglesFullDetail: 0,
};
window.museum = status;

const MB = 1e6;
// The loading bar: bytes of museum.glb received (of the total when the
// server says it).
function showProgress(e) {
  const bar = document.getElementById('progress');
  const text = e.total ? `loading museum.glb: ${(e.loaded / MB).toFixed(1)} of ${(e.total / MB).toFixed(1)} MB`
    : `loading museum.glb: ${(e.loaded / MB).toFixed(1)} MB`;
  bar.firstElementChild.style.width = e.total ? `${(100 * e.loaded / e.total).toFixed(1)}%` : '0';
  bar.lastElementChild.textContent = text;
  document.getElementById('stats').textContent = text;
  status.bytesLoaded = e.loaded;
  status.bytesTotal = e.total;
}

function fail(message) {
  status.error = message;
  document.getElementById('stats').textContent = message;
}

// The exhibits: nodes whose extras carry a title (museum_gltf.h).
function findExhibits(root) {
  const exhibits = [];
  root.traverse((o) => { if (o.userData && typeof o.userData.title === 'string') exhibits.push(o); });
  return exhibits;
}

// The entrance camera's pose, as the glTF puts it.
function entrancePose(gltf) {
  const cam = gltf.cameras[0];
  const position = new THREE.Vector3(), quaternion = new THREE.Quaternion();
  cam.getWorldPosition(position);
  cam.getWorldQuaternion(quaternion);
  return { position, quaternion, fov: cam.fov, aspect: cam.aspect };
}

function vesselCentre(exhibit) {
  const v = exhibit.userData.vessel;
  const p = new THREE.Vector3();
  v.getWorldPosition(p);
  p.y += exhibit.userData.height_cm / 200;  // half the vessel's height
  return p;
}

// Equirectangular Radiance .hdr probes, prefiltered for roughness (PMREM).
// three.js prefilters an equirectangular map into cube faces of at least
// 256 texels a side, whatever its own detail: for celadon's 128 x 64 probes
// (32 texels a side) that is 64 times the texels and, without a GPU
// (software WebGL), some 8 s of CPU a probe before the first frame. Faces of
// twice the probe's detail (64 texels) keep all of it for a sixth of the CPU
// (docs/BENCHMARKS.md, "Test suite"); _setSize is three.js's own step, its
// version pinned by web/package-lock.json.
async function loadProbes(renderer, scene, info, exhibits) {
  const pmrem = new THREE.PMREMGenerator(renderer);
  pmrem._setSize = (quarterWidth) => { pmrem._cubeSize = 2 * THREE.MathUtils.floorPowerOfTwo(quarterWidth); };
  const loader = new HDRLoader();
  const probe = async (url) => {
    const t = await loader.loadAsync(url);
    t.mapping = THREE.EquirectangularReflectionMapping;
    const env = pmrem.fromEquirectangular(t).texture;
    t.dispose();
    return env;
  };
  scene.environment = await probe(info.probe);
  await Promise.all(exhibits.map(async (e) => {
    const env = await probe(e.userData.probe);
    e.userData.vessel.traverse((o) => { if (o.isMesh) o.material.envMap = env; });
  }));
  pmrem.dispose();
  status.probes = 1 + exhibits.length;
}

async function main() {
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.xr.enabled = true;
  renderer.xr.setReferenceSpaceType('local-floor');
  document.body.appendChild(renderer.domElement);

  const gltf = await new GLTFLoader().loadAsync('museum.glb', showProgress);
  status.glbMs = performance.now();  // the file fetched and parsed (the first frames' and probes' times follow)
  document.getElementById('progress').style.display = 'none';
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x202020);
  scene.add(gltf.scene);
  const info = gltf.scene.children[0].userData.celadon_museum;
  status.title = info.title;
  document.getElementById('title').textContent = info.title;
  document.title = info.title;

  const lodInfo = makeLods(gltf.scene);
  const exhibits = findExhibits(gltf.scene);
  for (const e of exhibits) e.userData.vessel = lodInfo.vessels.find((v) => e.children.includes(v));
  status.vessels = exhibits.length;
  status.trianglesFullDetail = lodInfo.fullDetailTriangles;

  // The room's light comes from celadon's path tracer (docs/museum.md,
  // "Light"): floor, walls, ceiling and pedestals carry it baked (unlit
  // lightmaps), and each vessel's glaze is lit and mirrored by the probe
  // baked at its middle (the room as it sees it); the room's own probe, from
  // the entrance, lights the glass and the labels.
  // The probes are prefiltered after the first frames (in software WebGL
  // each takes about a second of CPU): the room shows at once, the glazes
  // and the glass take their reflections as their probes arrive
  // (docs/BENCHMARKS.md, "First frame").
  let firstFramesDrawn;
  const firstFrames = new Promise((resolve) => { firstFramesDrawn = resolve; });
  const probes = firstFrames.then(() => loadProbes(renderer, scene, info, exhibits));
  const lights = new LightPool(gltf.scene, scene);

  const pose = entrancePose(gltf);
  const camera = new THREE.PerspectiveCamera(pose.fov, window.innerWidth / window.innerHeight, 0.05, 500);
  const rig = new THREE.Group();  // the visitor's feet; the camera is the eyes
  rig.position.set(pose.position.x, 0, pose.position.z);
  camera.position.set(0, pose.position.y, 0);
  camera.quaternion.copy(pose.quaternion);
  rig.add(camera);
  scene.add(rig);

  const obstacles = new Obstacles(info, exhibits);
  const panel = new LabelPanel(scene);
  const pickables = exhibits;
  const walker = new Walker(camera, rig, renderer.domElement, obstacles);
  const xr = new XrLocomotion(renderer, rig, camera, scene, obstacles, pickables, walker,
    (hit) => panel.toggle(hit, camera));
  document.body.appendChild(VRButton.createButton(renderer));

  const raycaster = new THREE.Raycaster();
  // The exhibit under window pixel (x, y): its label opens (a pick of
  // nothing closes it); returns its title or null.
  status.pickAt = (x, y) => {
    const ndc = new THREE.Vector2((2 * x) / window.innerWidth - 1, 1 - (2 * y) / window.innerHeight);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObjects(pickables, true)[0];
    let o = hit ? hit.object : null;
    while (o && !(o.userData && typeof o.userData.title === 'string')) o = o.parent;
    if (o) panel.show(o, camera);
    else panel.hide();
    return o ? o.userData.title : null;
  };
  walker.pick = () => status.pickAt(window.innerWidth / 2, window.innerHeight / 2);
  const touch = new TouchControls(camera, renderer.domElement, walker, (x, y) => { status.lastTap = status.pickAt(x, y); });
  // For the tests: where the visitor stands and looks, the open label, and
  // thumbsticks emulated as WebXR input sources.
  status.pose = () => {
    const d = new THREE.Vector3();
    camera.getWorldDirection(d);
    return { x: rig.position.x, z: rig.position.z, yawDeg: Math.atan2(-d.x, -d.z) * 180 / Math.PI };
  };
  // Puts the eyes at (x, eyeY, z) looking toward (tx, ty, tz), without the
  // page's prompts: the docs' views.
  // The page's prompts and buttons over the view, shown or hidden (the
  // tests' and docs' views are of the room alone).
  status.overlays = (visible) => {
    for (const id of ['start', 'hud', 'crosshair', 'VRButton']) {
      const e = document.getElementById(id);
      if (e) e.style.visibility = visible ? '' : 'hidden';
    }
  };
  status.lookFrom = (x, eyeY, z, tx, ty, tz) => {
    rig.position.set(x, 0, z);
    rig.quaternion.identity();
    camera.position.y = eyeY;
    camera.lookAt(tx, ty, tz);
    status.overlays(false);
  };
  status.label = () => (panel.open ? panel.exhibit.userData.title : null);
  // Fewer pixels per frame (the tests' input checks need frames, not pixels).
  status.setPixelRatio = (r) => renderer.setPixelRatio(r);
  status.floatingLabel = () => panel.floating !== null && panel.floating.parent === scene;
  status.emulateXr = (sources) => xr.emulate(sources);
  // Where each vessel's middle is on the window, in pixels.
  status.vesselScreenPositions = () => exhibits.map((e) => {
    const p = vesselCentre(e).project(camera);
    return { title: e.userData.title, x: (p.x + 1) / 2 * window.innerWidth, y: (1 - p.y) / 2 * window.innerHeight };
  });
  status.setVesselsVisible = (visible) => { for (const v of lodInfo.vessels) v.visible = visible; };
  // Each vessel's lowest and highest point as drawn (m, world y).
  status.vesselHeights = () => exhibits.map((e) => {
    const box = new THREE.Box3().setFromObject(e.userData.vessel);
    return { bottom: box.min.y, top: box.max.y };
  });
  // Exhibit k's footprint centre (x, z), side w, its vessel's middle height
  // y and its label plate's height.
  status.casePosition = (k) => {
    const e = exhibits[k];
    const plate = e.children.find((c) => c.isMesh && c.name.startsWith('Label'));
    const p = new THREE.Vector3(), l = new THREE.Vector3();
    e.getWorldPosition(p);
    plate.getWorldPosition(l);
    const box = new THREE.Box3().setFromObject(e.children.find((c) => c.isMesh && c.name.startsWith('Pedestal')));
    return { x: p.x, z: p.z, w: box.max.x - box.min.x, y: vesselCentre(e).y, label: l.y };
  };

  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });

  const clock = new THREE.Clock();
  const stats = document.getElementById('stats');
  let sinceHud = 1, frames = 0;
  renderer.setAnimationLoop(() => {
    const dt = Math.min(clock.getDelta(), 0.1);
    walker.update(dt);
    touch.update(dt);
    xr.update(dt);
    const eye = new THREE.Vector3();
    camera.getWorldPosition(eye);
    lights.update(eye);
    panel.update(eye);
    renderer.render(scene, camera);
    status.triangles = renderer.info.render.triangles;
    status.drawCalls = renderer.info.render.calls;
    if (++frames === 3) {
      status.firstFrames = true;
      status.firstFramesMs = performance.now();
      firstFramesDrawn();
    }
    sinceHud += dt;
    if (sinceHud >= 0.5) {
      sinceHud = 0;
      stats.textContent = `${status.vessels} vessels; this frame: ${status.triangles.toLocaleString()} triangles, ` +
        `${status.drawCalls} draw calls (${status.trianglesFullDetail.toLocaleString()} triangles without LOD)`;
    }
  });
  // Ready (what the tests wait for): every probe in place, and a frame drawn with them.
  await probes;
  status.probesMs = performance.now();
  const drawn = frames;
  await new Promise((resolve) => {
    const wait = () => (frames > drawn ? resolve() : requestAnimationFrame(wait));
    wait();
  });
  status.ready = true;
}

main().catch((e) => fail(`cannot show the museum: ${e.message || e}`));
