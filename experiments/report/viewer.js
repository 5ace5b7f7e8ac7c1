// Image viewer of a bundlelab report: compare any two images (a method's final image, or a
// reference) by flipping, side by side, zoomed crops, exposure and false-colour error.
// Images arrive as base64 float16 RGB (linear radiance); everything is drawn on one canvas.
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("bl-images").textContent);
  const status = document.getElementById("bl-status");
  const canvas = document.getElementById("bl-canvas");
  const ctx = canvas.getContext("2d");
  const ui = (id) => document.getElementById(id);

  function halfToFloat(h) {
    const s = (h & 0x8000) ? -1 : 1, e = (h >> 10) & 0x1f, f = h & 0x3ff;
    if (e === 0) return s * Math.pow(2, -14) * (f / 1024);
    if (e === 31) return f ? NaN : s * Infinity;
    return s * Math.pow(2, e - 15) * (1 + f / 1024);
  }
  function decode(b64) {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const halves = new Uint16Array(bytes.buffer);
    const out = new Float32Array(halves.length);
    for (let i = 0; i < halves.length; ++i) out[i] = halfToFloat(halves[i]);
    return out;
  }
  const images = data.images.map((im) => ({ name: im.name, scene: im.scene, w: im.width, h: im.height, rgb: decode(im.data) }));

  const state = { a: 0, b: 1, mode: "split", exposure: 0, zoom: 1, panX: 0, panY: 0, split: 0.5, errorScale: 0.1, flip: false };

  function srgb(v) {
    v = v <= 0 ? 0 : v >= 1 ? 1 : v;
    return 255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055);
  }
  const ramp = [[0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];
  function colour(t) {
    t = Math.max(0, Math.min(1, t)) * 4;
    const i = Math.min(3, Math.floor(t)), f = t - i;
    return ramp[i].map((c, k) => 255 * (c + (ramp[i + 1][k] - c) * f));
  }

  function populate() {
    for (const id of ["bl-a", "bl-b"]) {
      const sel = ui(id);
      images.forEach((im, i) => {
        const o = document.createElement("option");
        o.value = i;
        o.textContent = im.scene + " / " + im.name;
        sel.appendChild(o);
      });
    }
    // A: the first method's image; B: the reference of its scene (or the next image).
    state.a = Math.max(0, images.findIndex((im) => !im.name.startsWith("reference")));
    const ref = images.findIndex((im) => im.name.startsWith("reference") && im.scene === images[state.a].scene);
    state.b = ref >= 0 ? ref : Math.min(state.a + 1, images.length - 1);
    ui("bl-a").value = state.a;
    ui("bl-b").value = state.b;
  }

  function draw() {
    const A = images[state.a], B = images[state.b];
    const w = A.w, h = A.h;
    // Small images are enlarged to about 512 pixels wide (nearest texel), then zoomed.
    const base = Math.max(1, Math.floor(512 / w)), z = state.zoom * base;
    canvas.width = w * base;
    canvas.height = h * base;
    const out = ctx.createImageData(canvas.width, canvas.height);
    const gain = Math.pow(2, state.exposure);
    const sameSize = B.w === A.w && B.h === A.h;
    for (let y = 0; y < canvas.height; ++y) {
      for (let x = 0; x < canvas.width; ++x) {
        // Nearest texel of the zoomed, panned view.
        const sx = Math.min(w - 1, Math.floor(x / z + state.panX)), sy = Math.min(h - 1, Math.floor(y / z + state.panY));
        const i = 3 * (sy * w + sx), o = 4 * (y * canvas.width + x);
        let rgb;
        let useB = state.mode === "b" || (state.mode === "flip" && state.flip) ||
                   (state.mode === "split" && x >= state.split * canvas.width);
        if (state.mode === "error" && sameSize) {
          let e = 0;
          for (let c = 0; c < 3; ++c) {
            const d = A.rgb[i + c] - B.rgb[i + c];
            e += d * d / (B.rgb[i + c] * B.rgb[i + c] + 0.01) / 3;
          }
          rgb = colour(e / state.errorScale);
        } else {
          const src = useB && sameSize ? B.rgb : A.rgb;
          rgb = [srgb(gain * src[i]), srgb(gain * src[i + 1]), srgb(gain * src[i + 2])];
        }
        out.data[o] = rgb[0]; out.data[o + 1] = rgb[1]; out.data[o + 2] = rgb[2]; out.data[o + 3] = 255;
      }
    }
    ctx.putImageData(out, 0, 0);
    if (state.mode === "split") {
      ctx.fillStyle = "#ff0";
      ctx.fillRect(Math.round(state.split * canvas.width), 0, 1, canvas.height);
    }
    ui("bl-caption").textContent =
      (state.mode === "error" ? "relMSE per pixel of A against B, scale 0.." + state.errorScale
        : state.mode === "split" ? "left: " + A.name + ", right: " + B.name
        : (state.mode === "b" || state.flip ? B.name : A.name)) +
      (sameSize ? "" : " (B has another size: showing A)") + ", exposure " + state.exposure + " EV, zoom " + state.zoom + "x";
  }

  function bind() {
    ui("bl-a").onchange = (e) => { state.a = +e.target.value; draw(); };
    ui("bl-b").onchange = (e) => { state.b = +e.target.value; draw(); };
    ui("bl-mode").onchange = (e) => { state.mode = e.target.value; draw(); };
    ui("bl-exposure").oninput = (e) => { state.exposure = +e.target.value; draw(); };
    ui("bl-zoom").onchange = (e) => { state.zoom = +e.target.value; state.panX = state.panY = 0; draw(); };
    ui("bl-error-scale").onchange = (e) => { state.errorScale = +e.target.value; draw(); };
    ui("bl-flip").onclick = () => { state.flip = !state.flip; draw(); };
    let dragging = null;
    canvas.onmousedown = (e) => { dragging = { x: e.offsetX, y: e.offsetY, px: state.panX, py: state.panY }; };
    window.onmouseup = () => { dragging = null; };
    canvas.onmousemove = (e) => {
      if (state.mode === "split" && !dragging) { state.split = e.offsetX / canvas.width; draw(); return; }
      if (!dragging) return;
      const A = images[state.a], scale = state.zoom * canvas.width / A.w;
      state.panX = Math.max(0, Math.min(A.w - A.w / state.zoom, dragging.px - (e.offsetX - dragging.x) / scale));
      state.panY = Math.max(0, Math.min(A.h - A.h / state.zoom, dragging.py - (e.offsetY - dragging.y) / scale));
      draw();
    };
    window.onkeydown = (e) => { if (e.key === "f") { state.flip = !state.flip; draw(); } };
  }

  window.addEventListener("error", () => status.setAttribute("data-status", "error"));
  populate();
  bind();
  draw();
  status.setAttribute("data-status", "ok");
  status.textContent = images.length + " images loaded";
})();
