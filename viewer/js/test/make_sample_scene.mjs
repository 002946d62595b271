// Writes test/sample_scene.json: a small scene for developing the viewer
// without the C++ tool. The mechanism mirrors models/4dof_reduced.yaml (three
// omni bases 0.58 m from the centre, a post on each with a passive vertical
// revolute, one link per leg up to a triangular platform at z = 0.6, revolute
// joints with horizontal axes). Over 30 frames (0.1 s apart) the platform
// moves 0.1 m in +y and sinks 0.05 m; the bases follow (and move out a little,
// the links being rigid) and turn. Frame 20 is flagged to show the marker.
//   node test/make_sample_scene.mjs > test/sample_scene.json
const N = 30, DT = 0.1;
const POST = 0.25, BASE_TOP = 0.1, LINK = 0.5, VERTEX = 0.15;  // [m]
const angles = [90, 210, 330].map((a) => (a * Math.PI) / 180);
const round = (x) => Math.round(x * 1e7) / 1e7;
const smooth = (s) => s * s * (3 - 2 * s);
// Quaternion [x, y, z, w] of a rotation by `angle` about the unit `axis`.
const quat = (axis, angle) => [...axis.map((a) => a * Math.sin(angle / 2)), Math.cos(angle / 2)];

const bodies = [{ name: 'ee', kind: 'body',
                  points: [...angles.map((a) => [VERTEX * Math.cos(a), VERTEX * Math.sin(a), 0]), [0, 0, 0]],
                  links: [[0, 1], [1, 2], [2, 0], [3, 0], [3, 1], [3, 2]] }];
const joints = [];
// Home: the link rises 0.25 m over 0.433 m of horizontal distance.
const homeRise = 0.6 - (BASE_TOP + POST), homeRun = Math.sqrt(LINK * LINK - homeRise * homeRise);
angles.forEach((a, i) => {
  const u = [Math.cos(a), Math.sin(a)];
  const half = [-u[0] * homeRun / 2, -u[1] * homeRun / 2, homeRise / 2];  // link's upper end - centre
  bodies.push({ name: `post${i}`, kind: 'body', points: [[0, 0, 0], [0, 0, POST]], links: [[0, 1]] });
  bodies.push({ name: `link${i}`, kind: 'body', points: [half.map((v) => -v), half].map((p) => p.map(round)),
                links: [[0, 1]] });
});
angles.forEach((a, i) => bodies.push({ name: `base${i}`, kind: 'omni', points: [[0, 0, 0], [0, 0, BASE_TOP]],
                                       links: [[0, 1]], radius: 0.13 }));
angles.forEach((a, i) => {
  const tangent = [-Math.sin(a), Math.cos(a), 0].map(round);
  const post = 1 + 2 * i, link = post + 1, base = 7 + i;
  joints.push({ name: `joint${3 * i}`, type: 'revolute', body: base, point: [0, 0, BASE_TOP], axis: [0, 0, 1],
                actuated: false });
  joints.push({ name: `joint${3 * i + 1}`, type: 'revolute', body: post, point: [0, 0, POST], axis: tangent,
                actuated: false });
  joints.push({ name: `joint${3 * i + 2}`, type: 'revolute', body: link, point: bodies[link].points[1],
                axis: tangent, actuated: false });
});

const time = [], poses = [], flags = [], tracked = [], commanded = [], bases = angles.map(() => []);
for (let f = 0; f < N; ++f) {
  const s = smooth(f / (N - 1));
  const cy = 0.1 * s, cz = 0.6 - 0.05 * s;
  const rise = cz - (BASE_TOP + POST), run = Math.sqrt(LINK * LINK - rise * rise);
  const tilt = Math.atan2(rise, run) - Math.atan2(homeRise, homeRun);  // link's pitch change from home
  const pose = [[0, cy, cz, 0, 0, 0, 1]];
  const basePoses = [];
  angles.forEach((a, i) => {
    const u = [Math.cos(a), Math.sin(a)];
    const bx = (VERTEX + run) * u[0], by = cy + (VERTEX + run) * u[1];
    // The link pitches about the horizontal tangent (z x u), through its centre.
    const tangent = [-Math.sin(a), Math.cos(a), 0];
    pose.push([bx, by, BASE_TOP, 0, 0, 0, 1]);
    pose.push([bx - u[0] * run / 2, by - u[1] * run / 2, BASE_TOP + POST + rise / 2, ...quat(tangent, tilt)]);
    basePoses.push([bx, by, 0, ...quat([0, 0, 1], a + 0.6 * s)]);
    bases[i].push([round(bx), round(by)]);
  });
  poses.push([...pose, ...basePoses].map((p) => p.map(round)));
  time.push(round(f * DT));
  flags.push(f === 20 ? 1 : 0);
  tracked.push([0, round(cy), round(cz)]);
  const ahead = smooth(Math.min(1, (f + 1) / (N - 1)));  // the target leads the platform by one frame
  commanded.push([0, round(0.1 * ahead), round(0.6 - 0.05 * ahead)]);
}

const scene = {
  format: 'ccma-scene-1',
  model: 'sample_3leg',
  description: 'Hand-made sample for viewer/js: 3 omni bases, posts, R-R legs, a triangular platform; ' +
               'the platform moves 0.1 m in y and sinks 0.05 m, the bases follow.',
  scale: 0.64,
  bodies,
  joints,
  end_effector: { body: 0, point: [0, 0, 0] },
  frames: { time, poses, flags },
  paths: { commanded, tracked, bases },
  source: 'trajectory',
};
process.stdout.write(JSON.stringify(scene) + '\n');
