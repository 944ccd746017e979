// What the browser tests share: Debian's chromium, headless, driven by playwright-core;
// a page that collects its console errors; and checks that print ok / FAIL and count.
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

export const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");

export function launchBrowser() {
  return chromium.launch({
    executablePath: "/usr/bin/chromium",
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
}

// A page of its own, and the errors its console and scripts report.
export async function openPage(browser, viewport = { width: 1400, height: 1000 }) {
  const page = await browser.newPage({ viewport });
  const consoleErrors = [];
  page.on("console", (message) => { if (message.type() === "error") consoleErrors.push(message.text()); });
  page.on("pageerror", (error) => consoleErrors.push(error.message));
  return { page, consoleErrors };
}

export class Checks {
  failures = 0;
  check(condition, what) {
    console.log(`${condition ? "ok  " : "FAIL"} ${what}`);
    if (!condition) this.failures += 1;
  }
  // Prints the verdict and ends the process with its status.
  finish(what) {
    console.log(this.failures === 0 ? `${what}: every check passed` : `${this.failures} checks failed`);
    process.exit(this.failures === 0 ? 0 : 1);
  }
}
