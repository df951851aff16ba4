// The HTML report's behaviour (report.tpl). A and B travel as linear float16 RGB in base64, not as 8-bit
// pictures, so that the exposure control can bring out what a fixed tone mapping would clip or crush: each
// change re-runs exposure and the sRGB transfer function (as verifier/metrics/srgb.h) on every canvas. Plain
// JavaScript with no library, since the page must open anywhere without the network. When every canvas is
// drawn the script sets document.body.dataset.ready = "1", which the headless browser test waits for.
'use strict';

(function () {
  // Every float16 bit pattern as a float32, built once: decoding is then a table look-up per value.
  const HALF_TO_FLOAT = (function () {
    const table = new Float32Array(65536);
    for (let bits = 0; bits < 65536; ++bits) {
      const sign = bits & 0x8000 ? -1 : 1;
      const exponent = (bits >> 10) & 0x1f;
      const mantissa = bits & 0x3ff;
      let magnitude;
      if (exponent === 0) {
        magnitude = mantissa * Math.pow(2, -24);
      } else if (exponent === 31) {
        magnitude = mantissa ? NaN : Infinity;
      } else {
        magnitude = (1 + mantissa / 1024) * Math.pow(2, exponent - 15);
      }
      table[bits] = sign * magnitude;
    }
    return table;
  })();

  // Little-endian float16 values, as html_report.cpp writes them.
  function decodeHalfs(base64) {
    const bytes = atob(base64);
    const values = new Float32Array(bytes.length >> 1);
    for (let i = 0; i < values.length; ++i) {
      values[i] = HALF_TO_FLOAT[bytes.charCodeAt(2 * i) | (bytes.charCodeAt(2 * i + 1) << 8)];
    }
    return values;
  }

  // verifier/metrics/srgb.h: clamped to [0, 1], a value that is not finite to 0, then IEC 61966-2-1.
  function encodeSrgb(linear) {
    const c = Number.isFinite(linear) ? Math.min(Math.max(linear, 0), 1) : 0;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
  }

  function toneMap(values, width, height, stops) {
    const scale = Math.pow(2, stops);
    const image = new ImageData(width, height);
    const out = image.data;
    for (let p = 0, n = width * height; p < n; ++p) {
      out[4 * p] = Math.round(255 * encodeSrgb(scale * values[3 * p]));
      out[4 * p + 1] = Math.round(255 * encodeSrgb(scale * values[3 * p + 1]));
      out[4 * p + 2] = Math.round(255 * encodeSrgb(scale * values[3 * p + 2]));
      out[4 * p + 3] = 255;
    }
    return image;
  }

  function formatValue(v) {
    return Number.isFinite(v) ? v.toPrecision(4) : String(v);
  }

  // One comparison: its two images on the side-by-side canvases and on the wipe, with their controls.
  class Entry {
    constructor(section) {
      this.section = section;
      this.width = Number(section.dataset.width);
      this.height = Number(section.dataset.height);
      this.factor = Number(section.dataset.factor);
      const panelA = section.querySelector('canvas.image.a');
      const panelB = section.querySelector('canvas.image.b');
      this.a = this.decode(panelA, 'A');
      this.b = this.decode(panelB, 'B');
      this.canvasesA = [panelA, section.querySelector('canvas.wipe-a')];
      this.canvasesB = [panelB, section.querySelector('canvas.wipe-b')];
      this.exposure = section.querySelector('input.exposure');
      this.exposureValue = section.querySelector('output.exposure-value');
      this.wipe = section.querySelector('.wipe');
      this.wipeA = section.querySelector('canvas.wipe-a');
      this.wipeLine = section.querySelector('.wipe-line');
      this.wipePosition = section.querySelector('input.wipe-position');
      this.flip = section.querySelector('button.flip');
      this.readout = section.querySelector('output.readout');
      this.exposure.addEventListener('input', () => this.draw());
      section.querySelector('button.exposure-reset').addEventListener('click', () => {
        this.exposure.value = '0';
        this.draw();
      });
      this.wipePosition.addEventListener('input', () => this.setWipe(Number(this.wipePosition.value)));
      this.flip.addEventListener('click', () => this.setWipe(Number(this.wipePosition.value) < 100 ? 100 : 0));
      this.wipe.addEventListener('pointerdown', (event) => {
        this.wipe.setPointerCapture(event.pointerId);
        this.setWipe(100 * this.fraction(event).x);
      });
      this.wipe.addEventListener('pointermove', (event) => {
        if (event.buttons) this.setWipe(100 * this.fraction(event).x);
        this.showValues(event);
      });
      this.wipe.addEventListener('pointerleave', () => {
        this.readout.textContent = 'point at the image for its values';
      });
      this.setWipe(50);
    }

    decode(canvas, name) {
      const values = decodeHalfs(canvas.dataset.pixels);
      if (values.length !== 3 * this.width * this.height) {
        throw new Error(this.section.id + ': image ' + name + ' holds ' + values.length + ' values, expected ' +
                        3 * this.width * this.height);
      }
      return values;
    }

    draw() {
      const stops = Number(this.exposure.value);
      this.exposureValue.textContent = (stops >= 0 ? '+' : '') + stops.toFixed(2);
      const imageA = toneMap(this.a, this.width, this.height, stops);
      const imageB = toneMap(this.b, this.width, this.height, stops);
      for (const canvas of this.canvasesA) canvas.getContext('2d').putImageData(imageA, 0, 0);
      for (const canvas of this.canvasesB) canvas.getContext('2d').putImageData(imageB, 0, 0);
      return this.canvasesA.length + this.canvasesB.length;
    }

    // 0..100: how much of the wipe, from the left, shows A.
    setWipe(percent) {
      const p = Math.min(Math.max(percent, 0), 100);
      this.wipePosition.value = String(p);
      this.wipeA.style.clipPath = 'inset(0 ' + (100 - p) + '% 0 0)';
      this.wipeLine.style.left = p + '%';
      this.flip.textContent = p < 100 ? 'show A' : 'show B';
    }

    fraction(event) {
      const box = this.wipe.getBoundingClientRect();
      return {
        x: Math.min(Math.max((event.clientX - box.left) / box.width, 0), 1),
        y: Math.min(Math.max((event.clientY - box.top) / box.height, 0), 1),
      };
    }

    showValues(event) {
      const f = this.fraction(event);
      const x = Math.min(Math.floor(f.x * this.width), this.width - 1);
      const y = Math.min(Math.floor(f.y * this.height), this.height - 1);
      const i = 3 * (y * this.width + x);
      const rgb = (values) => [0, 1, 2].map((c) => formatValue(values[i + c])).join(' ');
      const place = this.factor > 1
        ? 'block (' + x * this.factor + ', ' + y * this.factor + ') mean'
        : '(' + x + ', ' + y + ')';
      this.readout.textContent = place + '  A ' + rgb(this.a) + '  B ' + rgb(this.b);
    }
  }

  let drawn = 0;
  for (const section of document.querySelectorAll('section.entry')) drawn += new Entry(section).draw();
  document.body.dataset.canvases = String(drawn);
  // Ready once the heatmaps have decoded too: a PNG that does not decode shows only as a broken-image icon, so
  // it is made an error here.
  const heatmaps = Array.from(document.querySelectorAll('img.heatmap'));
  Promise.all(heatmaps.map((img) => img.decode().catch(() => {
    throw new Error('the heatmap "' + img.alt + '" does not decode');
  }))).then(() => {
    document.body.dataset.ready = '1';
  });
})();
