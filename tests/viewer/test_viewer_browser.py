"""`skyspec view` driven in a real browser (Debian's Chromium through ChromeDriver and Selenium).

The page loads and shows a frame; moving the sun slider with the keyboard brings a different one;
a click on the sky plots a spectrum; Export writes files identical to `skyspec render --scene` of
the exported TOML, and the frame the page shows has the pixels of that render's PNG. The server
refuses a non-loopback address unless asked, answers bad queries with 400 naming the key (and keeps
serving), and stops cleanly on SIGINT.

usage: test_viewer_browser.py SKYSPEC_PROGRAM
"""

import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

import numpy as np
import OpenImageIO as oiio
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import WebDriverWait

SKYSPEC = os.path.abspath(sys.argv[1])
# A cold default table build may run first in a clean clone (tests share the cache).
FIRST_FRAME_TIMEOUT_S = 300
TIMEOUT_S = 120


def check(condition, message):
    if not condition:
        raise SystemExit("FAIL: " + message)
    print("ok:", message)


def start_server(folder, *extra):
    proc = subprocess.Popen([SKYSPEC, "view", "--port", "0", "--out", os.path.join(folder, "exports"),
                             "--threads", "2", *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=folder)
    line = proc.stdout.readline()
    check(line.startswith("skyspec view: serving http://127.0.0.1:"), "the server prints its address: " + line.strip())
    url = line.split()[3]
    return proc, url


def get(url, post=False):
    try:
        with urllib.request.urlopen(url, data=b"" if post else None, timeout=TIMEOUT_S) as r:
            return r.status, r.read(), dict(r.headers)
    except urllib.error.HTTPError as e:
        return e.code, e.read(), dict(e.headers)


def png_pixels(data_or_path):
    if isinstance(data_or_path, bytes):
        path = os.path.join(tempfile.mkdtemp(prefix="skyspec-viewer-png-"), "f.png")
        with open(path, "wb") as f:
            f.write(data_or_path)
    else:
        path = data_or_path
    image = oiio.ImageInput.open(path)
    check(image is not None, "OpenImageIO opens " + os.path.basename(path))
    pixels = image.read_image(format="uint8")
    image.close()
    return np.asarray(pixels)


def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    # Without the background-networking flags Chromium keeps trying to reach Google's hosts, which
    # this closed network refuses.
    for arg in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--window-size=900,640"]:
        options.add_argument(arg)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def frames(driver):
    return int(driver.execute_script("return window.skyspec.frames"))


def settled(driver):
    """The page shows the exact frame of its controls (no preview, nothing pending)."""
    return driver.execute_script("return window.skyspec.settled()")


def canvas_digest(driver):
    data = driver.execute_script("return document.getElementById('frame').toDataURL('image/png')")
    return hashlib.sha256(data.encode()).hexdigest()


def page_tests(url, folder):
    driver = browser()
    try:
        driver.get(url)
        WebDriverWait(driver, FIRST_FRAME_TIMEOUT_S).until(lambda d: frames(d) >= 1 and settled(d))
        check(driver.find_element(By.ID, "error").text == "", "the first frame arrives without an error")
        size = driver.execute_script("return window.skyspec.frameSize")
        check(size[0] >= 64 and size[1] >= 64, f"the frame has the page's size ({size[0]} x {size[1]})")
        first = canvas_digest(driver)

        # The sun slider, moved as a user would: focus it and press keys.
        slider = driver.find_element(By.ID, "sun-elevation")
        before = float(slider.get_attribute("value"))
        seen = frames(driver)
        slider.click()
        slider.send_keys(Keys.PAGE_UP)
        after = float(slider.get_attribute("value"))
        check(after != before, f"the sun slider moved from {before} to {after} degrees")
        WebDriverWait(driver, TIMEOUT_S).until(lambda d: frames(d) > seen and settled(d))
        check(canvas_digest(driver) != first, "moving the sun changes the image")
        check(f"sun.elevation_deg={after}" in driver.execute_script("return window.skyspec.lastQuery"),
              "the frame shown is of the new sun elevation")

        # A click on the sky: the spectrum there.
        canvas = driver.find_element(By.ID, "frame")
        ActionChains(driver).move_to_element(canvas).click().perform()
        WebDriverWait(driver, TIMEOUT_S).until(lambda d: d.execute_script("return !!window.skyspecSpectrum"))
        spectrum = driver.execute_script("return window.skyspecSpectrum")
        wl, total, single = spectrum["wavelengths_nm"], spectrum["radiance"], spectrum["single_scattering"]
        check(len(wl) == len(total) == len(single) == 41, "the spectrum has the scene's 41 wavelengths")
        check(all(v > 0 and np.isfinite(v) for v in total), "its radiance is finite and positive")
        check(all(0 < s <= t for s, t in zip(single, total)), "single scattering is a share of the total")
        check("single scattering" in driver.find_element(By.ID, "spectrum-caption").text, "the plot is captioned")

        # Export: the files `skyspec render --scene` writes for the exported TOML.
        driver.find_element(By.ID, "export").click()
        WebDriverWait(driver, TIMEOUT_S).until(lambda d: d.execute_script("return !!window.skyspecExport"))
        exported = driver.execute_script("return window.skyspecExport")
        toml = os.path.join(folder, exported["scene"])
        check(os.path.isfile(toml), "Export wrote " + exported["scene"])
        again = os.path.join(folder, "again")
        subprocess.run([SKYSPEC, "render", "--scene", toml, "--out", again, "-q"], check=True, cwd=folder)
        for f in exported["files"]:
            name = os.path.basename(f)
            with open(os.path.join(folder, f), "rb") as a, open(os.path.join(again, name), "rb") as b:
                check(a.read() == b.read(), f"exported {name} is byte for byte skyspec render --scene's")

        # The frame the page shows for that query has the pixels of the CLI's PNG of the same scene.
        status, body, _ = get(url + "api/frame?" + driver.execute_script("return window.skyspec.lastQuery"))
        check(status == 200, "the page's frame again")
        png = [f for f in exported["files"] if f.endswith(".png")][0]
        check(np.array_equal(png_pixels(body), png_pixels(os.path.join(again, os.path.basename(png)))),
              "the viewer's frame has the same pixels as skyspec render's PNG of the exported scene")

        # The polarisation view.
        seen = frames(driver)
        digest = canvas_digest(driver)
        driver.execute_script("const m = document.getElementById('mode'); m.value = 'polarisation';"
                              "m.dispatchEvent(new Event('input'));")
        # A polarised render has vector tables of its own: where they are not cached (a clean clone)
        # the page shows single-scattering previews while they are built; any frame of the mode will do.
        WebDriverWait(driver, TIMEOUT_S).until(
            lambda d: frames(d) > seen and d.execute_script("return !window.skyspec.inFlight && !window.skyspec.dirty"
                                                            " && window.skyspec.settleTimer === null"))
        check(canvas_digest(driver) != digest and driver.find_element(By.ID, "error").text == "",
              "the polarisation view shows another picture")

        # A bad value typed into a field: the page shows the server's message, naming the key.
        driver.execute_script("const m = document.getElementById('mode'); m.value = 'colour';"
                              "const l = document.getElementById('latitude'); l.value = '123';"
                              "document.getElementById('use-date').checked = true;"
                              "l.dispatchEvent(new Event('input'));")
        WebDriverWait(driver, TIMEOUT_S).until(lambda d: d.find_element(By.ID, "error").text != "")
        error = driver.find_element(By.ID, "error").text
        check("location.latitude_deg" in error, "a latitude of 123 is refused by name on the page: " + error)
    finally:
        driver.quit()


def server_tests(url, folder):
    for query, key in [("sun.elevation_deg=abc", "sun.elevation_deg"), ("camera.width=4096&camera.height=4096", "camera.width"),
                       ("output.directory=%22/tmp%22", "output.directory"), ("view=Nope", "view"),
                       ("mode=x", "mode"), ("nonsense=1", "nonsense"), ("preset=venus", "preset")]:
        status, body, _ = get(url + "api/frame?" + query)
        answer = json.loads(body)
        check(status == 400 and answer["setting"] == key, f"{query}: 400 naming {key}: {answer['error']}")
    # Previews: asked for (a coarser sky-view table), and while a new atmosphere's tables are built
    # (single scattering; small tables of an aerosol load no other test uses, so they are not cached).
    small = "camera.width=32&camera.height=32&render.scattering_orders=2&render.ms_altitude_samples=8" \
            "&render.ms_sun_samples=24&render.ms_angular_degree=4"
    status, _, headers = get(url + "api/frame?camera.width=32&camera.height=32&render.scattering_orders=1&preview=1")
    check(status == 200 and headers["X-Skyspec-Preview"] == "coarse sky-view table", "a preview frame says so")
    fresh = small + f"&atmosphere.mie.scattering_per_m={1.1e-5 + 1e-9 * (os.getpid() % 1000)!r}" \
        + f"&atmosphere.ozone.column_DU={200 + time.time() % 100:.6f}"
    status, _, headers = get(url + "api/frame?" + fresh)
    check(status == 200 and headers["X-Skyspec-Preview"].startswith("single scattering"),
          "a new atmosphere's first frame is a single-scattering preview: " + headers["X-Skyspec-Preview"])
    start = time.time()
    while headers["X-Skyspec-Preview"] and time.time() - start < TIMEOUT_S:
        time.sleep(0.5)
        status, _, headers = get(url + "api/frame?" + fresh)
    check(status == 200 and headers["X-Skyspec-Preview"] == "",
          f"the exact frame follows once its tables are built ({time.time() - start:.1f} s)")
    status, body, headers = get(url + "api/spectrum?" + small + f"&atmosphere.ozone.column_DU={400 + time.time() % 100:.6f}"
                                "&x=1&y=1")
    check(status == 503 and headers.get("Retry-After") == "2" and "click again" in json.loads(body)["error"],
          "the spectrum of an atmosphere whose tables are not built yet: 503, ask again")
    status, body, _ = get(url + "api/frame?preview=2")
    check(status == 400 and json.loads(body)["setting"] == "preview", "preview=2: 400 naming preview")
    status, body, _ = get(url + "api/spectrum?x=-1&y=0")
    check(status == 400 and json.loads(body)["setting"] == "x", "a spectrum outside the image: 400 naming x")
    exports = os.listdir(os.path.join(folder, "exports"))
    # 9e8 pixels: about 160 GB of EXR and 60 GB of memory, beyond this kind of machine (24 GB).
    status, body, _ = get(url + "api/export?camera.width=30000&camera.height=30000", post=True)
    answer = json.loads(body)
    check(status == 400 and answer["setting"] == "export" and "beyond the budget" in answer["error"],
          "an export beyond the render budget is refused: " + answer["error"])
    check(os.listdir(os.path.join(folder, "exports")) == exports, "and writes nothing")
    status, body, _ = get(url + "no/such/page")
    check(status == 404, "an unknown page: 404")
    status, body, _ = get(url + "api/state")
    check(status == 200 and "sun.elevation_deg" in json.loads(body)["values"], "still serving after bad requests")


def main():
    folder = tempfile.mkdtemp(prefix="skyspec-viewer-")
    try:
        refused = subprocess.run([SKYSPEC, "view", "--host", "0.0.0.0", "--port", "0"], capture_output=True,
                                 text=True, timeout=60)
        check(refused.returncode == 2 and "--host" in refused.stderr and "--allow-remote" in refused.stderr,
              "a non-loopback --host is refused without --allow-remote: " + refused.stderr.strip())

        not_a_folder = os.path.join(folder, "file")
        open(not_a_folder, "w").close()
        refused = subprocess.run([SKYSPEC, "view", "--port", "0", "--out", not_a_folder], capture_output=True,
                                 text=True, timeout=60)
        check(refused.returncode == 2 and "--out" in refused.stderr, "--out naming a file is refused at once: "
              + refused.stderr.strip())

        proc, url = start_server(folder)
        try:
            page_tests(url, folder)
            server_tests(url, folder)
        finally:
            proc.send_signal(signal.SIGINT)
            try:
                out, err = proc.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                proc.kill()
                raise SystemExit("FAIL: the server did not stop within 20 s of SIGINT")
        check(proc.returncode == 0 and "stopped" in out, f"SIGINT stops the server cleanly (exit {proc.returncode})")
        leftovers = [f for f in os.listdir(os.path.join(folder, "exports")) if ".tmp-" in f]
        check(not leftovers, "no temporary file is left in the export folder")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print("viewer_browser: all checks passed")


if __name__ == "__main__":
    main()
