// The frames a student saved from the course's page: made here the way that page makes them, and
// checked by the server (POST /api/grade with `frames` parts) before the student hands them in.

// The course's page (hw2.js) on a clock of `hz` animation frames a second whose first frame comes
// `phaseMs` after the page starts: each animation frame draws with TIME, the previous frame's
// time, then saves frame k (toBlob of what it just drew) at the first frame whose timestamp passes
// k seconds, then sets TIME to this frame's time. Frame 0 is drawn at 0; frame k at 20k degrees
// less up to one frame interval of rotation (docs/homework-contract.md, "Frame timing and export").
// The drawings between saves change nothing that is saved, so only the saved ones are drawn.
export function coursePageAngles({ count, degreesPerFrame, hz, phaseMs }) {
  const intervalMs = 1000 / hz;
  const angles = [];
  let time = 0;  // TIME, in seconds: 0 until the first frame has been drawn
  for (let n = 0; angles.length < count; ++n) {
    const timestamp = phaseMs + n * intervalMs;
    if (timestamp / 1000 > angles.length) angles.push(degreesPerFrame * time);  // this frame is drawn at TIME, then saved
    time = timestamp / 1000;
  }
  return angles;
}

// The PNGs the course's page would save for the program now in `view`: [{name, degrees, lag, blob}].
export async function saveLikeTheCoursePage(view, course, prefix, clock) {
  const { count, degreesPerFrame } = course.frames;
  const angles = coursePageAngles({ count, degreesPerFrame, ...clock });
  const out = [];
  for (const [k, degrees] of angles.entries()) {
    const name = `${course.frames.fileName.replaceAll("{prefix}", prefix).replaceAll("{k}", String(k))}.png`;
    out.push({ name, degrees, lag: k * degreesPerFrame - degrees, blob: await view.captureFrame(degrees) });
  }
  return out;
}

// Which deliverable each dropped file is a frame of, by the course's names (hw2_specular_3.png):
// {checkpointName: [File]}, and the files that are no deliverable's frames.
export function groupByDeliverable(files, course) {
  const groups = {}, strays = [];
  const pattern = (prefix) => new RegExp(`^${course.frames.fileName.replaceAll("{prefix}", prefix).replaceAll("{k}", "\\d+")}\\.png$`);
  for (const file of files) {
    const checkpoint = course.checkpoints.find((c) => pattern(c.prefix).test(file.name));
    if (checkpoint) (groups[checkpoint.name] ??= []).push(file);
    else strays.push(file);
  }
  return { groups, strays };
}
