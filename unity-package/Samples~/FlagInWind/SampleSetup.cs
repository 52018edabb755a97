using UnityEngine;

namespace Drape.Samples.Flag
{
    /// <summary>Camera and light for the sample. Each sample folder has its own copy in its own
    /// namespace, so any set of samples imports and compiles together.</summary>
    internal static class SampleSetup
    {
        /// <summary>A camera at <paramref name="position"/> looking at <paramref name="target"/>, and a sun.</summary>
        public static Camera CameraAndLight(Vector3 position, Vector3 target)
        {
            Camera cam = Camera.main;
            if (cam == null)
            {
                var go = new GameObject("Camera");
                go.tag = "MainCamera";
                cam = go.AddComponent<Camera>();
            }
            cam.transform.position = position;
            cam.transform.LookAt(target);
            if (Object.FindAnyObjectByType<Light>() == null)
            {
                var sun = new GameObject("Sun").AddComponent<Light>();
                sun.type = LightType.Directional;
                sun.transform.rotation = Quaternion.Euler(50f, -30f, 0f);
            }
            return cam;
        }
    }
}
