// The celadon museum page: loads museum.glb (celadon museum, docs/museum.md),
// turns its levels of detail into THREE.LOD objects, keeps the nearest lights,
// and walks it on a desktop (walk.js) or in a WebXR headset (xr.js).
// window.museum reports what was loaded and what a frame costs (the tests and
// the HUD read it).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { VRButton } from 'three/addons/webxr/VRButton.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { makeLods } from './lod.js';
import { LightPool } from './light_pool.js';
import { Obstacles } from './obstacles.js';
import { Walker } from './walk.js';
import { XrLocomotion } from './xr.js';
import { LabelPanel } from './label_panel.js';

const status = {
  ready: false, error: null, title: '', vessels: 0,
  triangles: 0, drawCalls: 0, trianglesFullDetail: 0,
};
window.museum = status;

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

async function main() {
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.xr.enabled = true;
  renderer.xr.setReferenceSpaceType('local-floor');
  document.body.appendChild(renderer.domElement);

  const gltf = await new GLTFLoader().loadAsync('museum.glb');
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

  // No global illumination in a rasteriser: a dim room-like environment
  // stands in for the light the walls bounce (the path tracer computes it),
  // and gives the glaze's clear coat and the glass something to reflect.
  const pmrem = new THREE.PMREMGenerator(renderer);
  scene.environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
  scene.environmentIntensity = 0.35;
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
  const xr = new XrLocomotion(renderer, rig, scene, obstacles, pickables, (hit) => panel.show(hit, camera));
  document.body.appendChild(VRButton.createButton(renderer));

  const raycaster = new THREE.Raycaster();
  // The exhibit under window pixel (x, y), or null.
  status.pickAt = (x, y) => {
    const ndc = new THREE.Vector2((2 * x) / window.innerWidth - 1, 1 - (2 * y) / window.innerHeight);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObjects(pickables, true)[0];
    let o = hit ? hit.object : null;
    while (o && !(o.userData && typeof o.userData.title === 'string')) o = o.parent;
    if (o) panel.show(o, camera);
    return o ? o.userData.title : null;
  };
  walker.pick = () => status.pickAt(window.innerWidth / 2, window.innerHeight / 2);
  // Where each vessel's middle is on the window, in pixels.
  status.vesselScreenPositions = () => exhibits.map((e) => {
    const p = vesselCentre(e).project(camera);
    return { title: e.userData.title, x: (p.x + 1) / 2 * window.innerWidth, y: (1 - p.y) / 2 * window.innerHeight };
  });
  status.setVesselsVisible = (visible) => { for (const v of lodInfo.vessels) v.visible = visible; };

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
    xr.update();
    const eye = new THREE.Vector3();
    camera.getWorldPosition(eye);
    lights.update(eye);
    renderer.render(scene, camera);
    status.triangles = renderer.info.render.triangles;
    status.drawCalls = renderer.info.render.calls;
    if (++frames >= 3) status.ready = true;
    sinceHud += dt;
    if (sinceHud >= 0.5) {
      sinceHud = 0;
      stats.textContent = `${status.vessels} vessels; this frame: ${status.triangles.toLocaleString()} triangles, ` +
        `${status.drawCalls} draw calls (${status.trianglesFullDetail.toLocaleString()} triangles without LOD)`;
    }
  });
}

main().catch((e) => fail(`cannot show the museum: ${e.message || e}`));
