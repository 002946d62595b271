// Bodies' meshes (`ccma view --meshes`; viewer/scene_format.md, "meshes"):
// the scene carries each distinct STL file once, base64-encoded binary STL
// checked and rewritten by the C++ side, and every body lists its meshes'
// poses in its own frame. Parsed once with three.js's STLLoader; a mesh is a
// child of its body's group, so it moves with the body.
import { Box3, Mesh, Quaternion, Vector3 } from 'three';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { COLORS } from './colors.js';
import { material } from './shapes.js';

const isVec = (v, n) => Array.isArray(v) && v.length === n && v.every(Number.isFinite);

// Problems with the scene's mesh parts (none when it has no meshes).
export function checkMeshes(scene) {
  const problems = [];
  const files = scene.meshes;
  if (files === undefined) return problems;
  if (!Array.isArray(files)) return ['meshes: a list'];
  files.forEach((f, i) => {
    if (!f || typeof f.stl_base64 !== 'string' || !/^[A-Za-z0-9+/]*={0,2}$/.test(f.stl_base64)) {
      problems.push(`meshes[${i}].stl_base64: base64 text`);
    }
  });
  (scene.bodies || []).forEach((b, i) => {
    if (!b || b.meshes === undefined) return;
    if (!Array.isArray(b.meshes)) { problems.push(`bodies[${i}].meshes: a list`); return; }
    b.meshes.forEach((m, k) => {
      const where = `bodies[${i}].meshes[${k}]`;
      if (!m || !Number.isInteger(m.file) || m.file < 0 || m.file >= files.length) problems.push(`${where}.file: an index into meshes`);
      if (!m || !isVec(m.position, 3)) problems.push(`${where}.position: [x, y, z]`);
      if (!m || !isVec(m.quaternion, 4)) problems.push(`${where}.quaternion: [qx, qy, qz, qw]`);
      if (!m || !isVec(m.scale, 3) || !m.scale.every((s) => s > 0)) problems.push(`${where}.scale: three positive numbers`);
    });
  });
  return problems;
}

// The bytes of base64 `text`, as an ArrayBuffer.
export function decodeBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

// One BufferGeometry per entry of scene.meshes (empty without meshes).
export function meshGeometries(scene) {
  const loader = new STLLoader();
  return (scene.meshes || []).map((f) => loader.parse(decodeBase64(f.stl_base64)));
}

// Adds body's meshes to its `group`; returns the three.js meshes added.
export function addBodyMeshes(group, body, geometries) {
  const mat = material(COLORS.mesh, { roughness: 0.55, metalness: 0.1 });
  return (body.meshes || []).map((m) => {
    const mesh = new Mesh(geometries[m.file], mat);
    mesh.position.set(...m.position);
    mesh.quaternion.copy(new Quaternion(...m.quaternion).normalize());
    mesh.scale.set(...m.scale);
    mesh.name = `mesh ${m.file}`;
    group.add(mesh);
    return mesh;
  });
}

// The world box of `meshes` as posed now (empty box when there are none).
export function meshesBox(meshes) {
  const box = new Box3();
  meshes.forEach((m) => box.expandByObject(m));
  return box;
}

// The world position of every mesh's vertex centroid (tests).
export function meshCentroidsWorld(meshes) {
  return meshes.map((m) => {
    const position = m.geometry.getAttribute('position');
    const c = new Vector3();
    for (let i = 0; i < position.count; ++i) c.add(new Vector3().fromBufferAttribute(position, i));
    return m.localToWorld(c.divideScalar(Math.max(1, position.count)));
  });
}
