// The browser-vs-server measure (the same the fidelity test asserts): the share of pixels where
// some RGB channel differs by more than 8/255, and the mean absolute error over RGB in [0, 1].
// PSNR is the wrong yardstick here: two rasterisers place multisamples differently at edges.
// `interior` counts differing pixels whose whole 3 x 3 neighbourhood differs too: edge noise is
// one or two pixels wide, so anything there is a real mismatch (a wrong colour over an area).
export async function imageDataOf(blob) {
  const bitmap = await createImageBitmap(blob, { premultiplyAlpha: "none", colorSpaceConversion: "none" });
  const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
  const ctx = canvas.getContext("2d");
  ctx.drawImage(bitmap, 0, 0);
  return ctx.getImageData(0, 0, bitmap.width, bitmap.height);
}

export function compareImages(a, b, threshold = 8) {
  if (a.width !== b.width || a.height !== b.height) throw new Error(`sizes differ: ${a.width}x${a.height} vs ${b.width}x${b.height}`);
  const diff = new ImageData(a.width, a.height);
  const overMask = new Uint8Array(a.width * a.height);
  let over = 0, sum = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    let worst = 0;
    for (let c = 0; c < 3; ++c) {
      const d = Math.abs(a.data[i + c] - b.data[i + c]);
      sum += d;
      worst = Math.max(worst, d);
    }
    if (worst > threshold) ++over, (overMask[i / 4] = 1);
    const v = Math.min(255, worst * 16);
    diff.data.set(worst > threshold ? [255, 0, 0, 255] : [v, v, v, 255], i);
  }
  let interior = 0;
  for (let y = 1; y + 1 < a.height; ++y)
    for (let x = 1; x + 1 < a.width; ++x) {
      let all = true;
      for (let dy = -1; dy <= 1 && all; ++dy)
        for (let dx = -1; dx <= 1 && all; ++dx) all = overMask[(y + dy) * a.width + x + dx] === 1;
      if (all) ++interior;
    }
  const pixels = a.width * a.height;
  return { fractionOver: over / pixels, meanAbsError: sum / (pixels * 3 * 255), interior, diff };
}
