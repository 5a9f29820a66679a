//! The few functions of Open Image Denoise 2's C API that denoising one image needs, bound at run
//! time from the shared library.
//!
//! Why `unsafe`: calling into a C library loaded at run time cannot be done otherwise — the
//! symbols' types are the C header's promise (OpenImageDenoise/oidn.h of OIDN 2.x), which the
//! compiler cannot check. This module is the only place the workspace allows it; every block
//! says what it relies on.
#![allow(unsafe_code)]

use libloading::Library;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::Path;

type DevicePtr = *mut c_void;
type FilterPtr = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`: the CPU device (no probing for GPUs and their runtimes).
const DEVICE_TYPE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3`: three packed f32 per pixel.
const FORMAT_FLOAT3: c_int = 3;
/// `OIDN_ERROR_NONE`.
const ERROR_NONE: c_int = 0;

/// The functions used, with their C signatures (oidn.h, OIDN 2.x).
pub(crate) struct Api {
    new_device: unsafe extern "C" fn(c_int) -> DevicePtr,
    commit_device: unsafe extern "C" fn(DevicePtr),
    release_device: unsafe extern "C" fn(DevicePtr),
    get_device_error: unsafe extern "C" fn(DevicePtr, *mut *const c_char) -> c_int,
    new_filter: unsafe extern "C" fn(DevicePtr, *const c_char) -> FilterPtr,
    #[allow(clippy::type_complexity)]
    set_shared_filter_image:
        unsafe extern "C" fn(FilterPtr, *const c_char, *mut c_void, c_int, usize, usize, usize, usize, usize),
    set_filter_bool: unsafe extern "C" fn(FilterPtr, *const c_char, bool),
    commit_filter: unsafe extern "C" fn(FilterPtr),
    execute_filter: unsafe extern "C" fn(FilterPtr),
    release_filter: unsafe extern "C" fn(FilterPtr),
    /// Keeps the functions above valid; dropped last.
    _library: Library,
}

impl Api {
    /// Opens the library at `path` (a bare file name goes through the system's search path) and
    /// looks up every function; an error names what failed.
    pub(crate) fn load(path: &Path) -> Result<Self, String> {
        // SAFETY: loading runs the library's initialisers; Open Image Denoise's only register its
        // device modules. The path is one the user pointed at (OIDN_DIR) or a known install place.
        let library = unsafe { Library::new(path) }.map_err(|e| e.to_string())?;
        macro_rules! symbol {
            ($name:literal) => {
                // SAFETY: the symbol's type is the one oidn.h declares for it (copied above, in
                // the struct's field types); the pointer stays valid while `library` lives, and
                // `Api` keeps it alive as long as the pointers.
                *unsafe { library.get(concat!($name, "\0").as_bytes()) }
                    .map_err(|e| format!("{} lacks {}: {e}", path.display(), $name))?
            };
        }
        Ok(Self {
            new_device: symbol!("oidnNewDevice"),
            commit_device: symbol!("oidnCommitDevice"),
            release_device: symbol!("oidnReleaseDevice"),
            get_device_error: symbol!("oidnGetDeviceError"),
            new_filter: symbol!("oidnNewFilter"),
            set_shared_filter_image: symbol!("oidnSetSharedFilterImage"),
            set_filter_bool: symbol!("oidnSetFilterBool"),
            commit_filter: symbol!("oidnCommitFilter"),
            execute_filter: symbol!("oidnExecuteFilter"),
            release_filter: symbol!("oidnReleaseFilter"),
            _library: library,
        })
    }
}

/// A committed CPU device, released on drop.
pub(crate) struct Device {
    api: Api,
    ptr: DevicePtr,
}

// SAFETY: OIDN devices are thread-safe objects (the API documents that calls on one device from
// several threads are serialised by the library).
unsafe impl Send for Device {}
// SAFETY: as above.
unsafe impl Sync for Device {}

impl Device {
    pub(crate) fn new_cpu(api: Api) -> Result<Self, String> {
        // SAFETY: `oidnNewDevice` takes a device type by value and returns a new handle or null.
        let ptr = unsafe { (api.new_device)(DEVICE_TYPE_CPU) };
        if ptr.is_null() {
            return Err("no CPU device could be created (is the CPU supported: SSE4.1 or newer?)".into());
        }
        let device = Self { api, ptr };
        // SAFETY: `ptr` is the live device just created.
        unsafe { (device.api.commit_device)(device.ptr) };
        device.check()?;
        Ok(device)
    }

    /// The device's pending error, if any (reading it clears it).
    fn check(&self) -> Result<(), String> {
        let mut message: *const c_char = std::ptr::null();
        // SAFETY: `self.ptr` is live; the out-pointer is a valid place for one pointer.
        let code = unsafe { (self.api.get_device_error)(self.ptr, &mut message) };
        if code == ERROR_NONE {
            return Ok(());
        }
        let text = if message.is_null() {
            String::new()
        } else {
            // SAFETY: OIDN returns a NUL-terminated string valid until the next call on the device.
            unsafe { CStr::from_ptr(message) }.to_string_lossy().into_owned()
        };
        Err(format!("error {code}: {text}"))
    }

    /// Runs the "RT" filter (ray-traced images, HDR) on `width × height` packed RGB f32 images.
    pub(crate) fn denoise_rgb(
        &self,
        width: usize,
        height: usize,
        color: &[f32],
        albedo: &[f32],
        normal: &[f32],
    ) -> Result<Vec<f32>, String> {
        let len = width * height * 3;
        if [color.len(), albedo.len(), normal.len()].iter().any(|&l| l != len) {
            return Err(format!("image buffers must hold {len} values"));
        }
        let mut output = vec![0.0f32; len];
        // SAFETY: `self.ptr` is live and the name is NUL-terminated.
        let filter = unsafe { (self.api.new_filter)(self.ptr, c"RT".as_ptr()) };
        if filter.is_null() {
            self.check()?;
            return Err("the RT filter could not be created".into());
        }
        let stride = 3 * std::mem::size_of::<f32>();
        let images: [(&CStr, *mut c_void); 4] = [
            (c"color", color.as_ptr() as *mut c_void),
            (c"albedo", albedo.as_ptr() as *mut c_void),
            (c"normal", normal.as_ptr() as *mut c_void),
            (c"output", output.as_mut_ptr() as *mut c_void),
        ];
        for (name, data) in images {
            // SAFETY: `filter` is live; each buffer holds `len` f32 (checked above) laid out as
            // `height` rows of `width` packed FLOAT3 pixels, and outlives the filter's execution
            // below. OIDN only reads the inputs (the cast to *mut is the C API's signature).
            unsafe {
                (self.api.set_shared_filter_image)(
                    filter,
                    name.as_ptr(),
                    data,
                    FORMAT_FLOAT3,
                    width,
                    height,
                    0,
                    stride,
                    stride * width,
                )
            };
        }
        // SAFETY: `filter` is live; the names are NUL-terminated. Execution is synchronous, so the
        // shared buffers are not used after this block.
        unsafe {
            (self.api.set_filter_bool)(filter, c"hdr".as_ptr(), true);
            (self.api.commit_filter)(filter);
            (self.api.execute_filter)(filter);
        }
        let result = self.check();
        // SAFETY: `filter` is live and not used again.
        unsafe { (self.api.release_filter)(filter) };
        result.map(|()| output)
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: `self.ptr` is live and not used again; the library outlives this call (it is
        // dropped with `self.api` after this).
        unsafe { (self.api.release_device)(self.ptr) };
    }
}
