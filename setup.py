# The Python package (pneumatic_finger.core beside the generated pneumatic_finger.msg/.srv), for catkin.
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["pneumatic_finger"], package_dir={"": "python"}))
