"""docs/images/viewer.png: `skyspec view` in headless Chromium, a panorama at sunset with the
spectrum of a point near the horizon plotted.

usage: /usr/bin/python3 docs/images/make_viewer_screenshot.py build/skyspec docs/images/viewer.png
"""

import os
import signal
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "viewer"))
skyspec, target = sys.argv[1], os.path.abspath(sys.argv[2])
sys.argv = [sys.argv[0], skyspec]  # what the test module reads
import test_viewer_browser as viewer  # noqa: E402  (the test's browser and server helpers)
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402


def settled(driver, seen):
    return viewer.frames(driver) > seen and viewer.settled(driver)


folder = tempfile.mkdtemp(prefix="skyspec-screenshot-")
proc, url = viewer.start_server(folder)
driver = viewer.browser()
try:
    driver.set_window_size(1400, 900)
    driver.get(url)
    WebDriverWait(driver, viewer.FIRST_FRAME_TIMEOUT_S).until(lambda d: settled(d, 0))
    seen = viewer.frames(driver)
    driver.execute_script(
        "const set = (id, v) => { const e = document.getElementById(id); e.value = v; };"
        "set('camera', 'equirectangular'); set('sun-elevation', '3'); set('sun-azimuth', '250');"
        "set('aerosol', '40'); set('albedo', '0.25');"
        "document.getElementById('sun-elevation').dispatchEvent(new Event('input'));")
    WebDriverWait(driver, viewer.TIMEOUT_S).until(lambda d: settled(d, seen))
    canvas = driver.find_element(By.ID, "frame")
    # A point 8 degrees above the horizon, 40 degrees to the right of the sun (azimuth 290).
    size = canvas.size
    x = (290 / 360 - 0.5) * size["width"]
    y = (0.5 - (8 + 90) / 180) * size["height"]
    ActionChains(driver).move_to_element_with_offset(canvas, int(x), int(y)).click().perform()
    WebDriverWait(driver, viewer.TIMEOUT_S).until(lambda d: d.execute_script("return !!window.skyspecSpectrum"))
    driver.save_screenshot(target)
    print("wrote", target)
finally:
    driver.quit()
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=30)
